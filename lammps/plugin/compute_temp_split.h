/* compute temp/split: the kinetic temperature of the velocities at a chosen point inside the
   step of fix dpd/split (see docs/lammps.md in the dpd workspace). SPDX-License-Identifier: MIT */
#ifndef DPD_COMPUTE_TEMP_SPLIT_H
#define DPD_COMPUTE_TEMP_SPLIT_H

#include "compute.h"

#include <string>

namespace LAMMPS_NS {

class ComputeTempSplit : public Compute {
 public:
  ComputeTempSplit(class LAMMPS *, int, char **);
  ~ComputeTempSplit() override;
  void init() override;
  void setup() override;
  double compute_scalar() override;
  void compute_vector() override;

 private:
  std::string fix_id;
  /// The stage after which the velocities are taken (1-based, as the program prints them);
  /// 0 until init() resolves the default (the last O, Ob or T stage, else the step's end).
  int stage;
  class FixDPDSplit *fix;
  double tfactor;

  void dof_compute();
};

}    // namespace LAMMPS_NS

#endif
