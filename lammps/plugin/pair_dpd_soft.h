/* pair_style dpd/soft: the conservative force of DPD alone (see docs/lammps.md in the dpd
   workspace). SPDX-License-Identifier: MIT */
#ifndef DPD_PAIR_DPD_SOFT_H
#define DPD_PAIR_DPD_SOFT_H

#include "pair.h"

#include <vector>

namespace LAMMPS_NS {

class PairDPDSoft : public Pair {
 public:
  PairDPDSoft(class LAMMPS *);
  ~PairDPDSoft() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  /// The per type-pair strengths and cutoffs (see `a`, `cut`), symmetric once LAMMPS's init
  /// has run: fix dpd/split's T stages include this force in their exact pair update.
  const double *strengths() const { return a.data(); }
  const double *cutoffs() const { return cut.data(); }

 private:
  double cut_global;
  /// Per type pair (row-major, (ntypes + 1)^2, row and column 0 unused): the strength a and
  /// the cutoff r_c, as the kernels take them.
  std::vector<double> a, cut;
  /// The special-bond factors of the current run (force->special_lj).
  double special[4];

  void allocate();
  /// The index of type pair (i, j) in `a` and `cut`.
  int slot(int i, int j) const;
};

}    // namespace LAMMPS_NS

#endif
