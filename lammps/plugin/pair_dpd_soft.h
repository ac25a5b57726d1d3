/* pair_style dpd/soft: the conservative force of DPD alone (see docs/lammps.md in the dpd
   workspace). SPDX-License-Identifier: MIT */
#ifndef DPD_PAIR_DPD_SOFT_H
#define DPD_PAIR_DPD_SOFT_H

#include "dpd_lammps.h"
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
  /// Record in `record` (fix dpd/split's, which colours its atoms) the pairs within the fix's
  /// cutoff (less those of special factor 0, which get no force and which the fix's sweeps
  /// exclude) of every evaluation of this run (the fix asks for it in its init(), after this
  /// style's init_style() has reset it): the fix's sweeps at the positions
  /// of the last evaluation take them from the record instead of passing over the neighbour
  /// list. `recordings()` counts the evaluations recorded.
  void record_pairs(DpdLammpsRecord *record) { pair_record = record; }
  long long recordings() const { return recorded; }

 private:
  double cut_global;
  /// Per type pair (row-major, (ntypes + 1)^2, row and column 0 unused): the strength a and
  /// the cutoff r_c, as the kernels take them.
  std::vector<double> a, cut;
  /// The special-bond factors of the current run (force->special_lj).
  double special[4];
  /// The record of the fix that asked (not owned), null when none did.
  DpdLammpsRecord *pair_record;
  long long recorded;

  void allocate();
  /// The index of type pair (i, j) in `a` and `cut`.
  int slot(int i, int j) const;
};

}    // namespace LAMMPS_NS

#endif
