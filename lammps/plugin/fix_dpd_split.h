/* fix dpd/split: one step of an exported splitting scheme of DPD per LAMMPS step (see
   docs/lammps.md in the dpd workspace). SPDX-License-Identifier: MIT */
#ifndef DPD_FIX_DPD_SPLIT_H
#define DPD_FIX_DPD_SPLIT_H

#include "dpd_lammps.h"
#include "fix.h"
#include "schemes.h"

#include <array>
#include <vector>

namespace LAMMPS_NS {

class FixDPDSplit : public Fix {
 public:
  FixDPDSplit(class LAMMPS *, int, char **);
  ~FixDPDSplit() override;
  int setmask() override;
  void init() override;
  void init_list(int, class NeighList *) override;
  void setup(int) override;
  void setup_pre_force(int) override;
  void pre_force(int) override;
  void initial_integrate(int) override;
  void final_integrate() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;

  /// For compute temp/split: the number of stages of the scheme, its program, the stage
  /// (1-based) after which its last O, Ob or T stage leaves the velocities (the step's last
  /// stage if it has none), and the local sums `m v_a v_b` (xx, yy, zz, xy, xz, yz) of the
  /// velocities after a stage, which the fix records during each step once asked to.
  int stage_count() const { return scheme->nstages; }
  const char *program() const { return scheme->program; }
  int thermostat_stage() const;
  void record_kinetic(int stage);
  const double *kinetic(int stage) const { return kinetic_sums[stage].data(); }

 private:
  const DpdSplit::Scheme *scheme;
  double kt, exponent;
  /// Per pair of atom types (row-major, (ntypes + 1)^2, row and column 0 unused): the
  /// friction gamma_IJ and cutoff r_c,IJ of the dissipative and random weights, as pair dpd's
  /// pair_coeff sets them; `max_rc` is the largest.
  std::vector<double> gamma, rc;
  double max_rc;
  unsigned long long seed;
  /// Refuse other integrators and pair styles with their own DPD thermostat (keyword
  /// `exclusive`, default yes).
  bool exclusive;
  /// Energy and virial on the steps LAMMPS tallies them: at the step's final positions, with a
  /// force evaluation of their own if the step ends with a drift (keyword `tally end`, the
  /// default), or as LAMMPS's evaluation within the step tallied them (`tally evaluation`).
  bool tally_end;
  DpdLammpsKernels *kernels;
  class NeighList *list;
  /// The conservative force of T stages (null when the scheme has none), set by init().
  const class PairDPDSoft *soft;
  /// The pair style when it is dpd/soft and the scheme sweeps: it records the pairs within the
  /// fix's cutoff at each evaluation into `pair_record`, by the colours the fix gives it
  /// (`colour_atoms_of_list`, before each evaluation); `record_seen` is its count of
  /// recordings when the fix last looked, and the last recording was at drift count
  /// `record_moves` and neighbour-list build `record_build` (see `recorded()`).
  class PairDPDSoft *recorder;
  DpdLammpsRecord *pair_record;
  long long record_seen, record_moves;
  bigint record_build;

  /// Stages [0, split) run in initial_integrate, the rest in final_integrate, so that
  /// LAMMPS's own force evaluation falls at the first stage needing forces after a drift.
  int split;
  /// The index of the step's last drift (A) stage, -1 if none.
  int last_drift;
  /// Positions changed since forces, or since ghost positions, were last computed.
  bool forces_stale, ghosts_stale;
  /// The energy and virial flags of the current step (0 on steps without thermo output).
  int step_eflag, step_vflag;
  /// Counts position changes and re-neighbourings; the F evaluation is reused while it holds.
  long long epoch, full_epoch;
  /// Counts drifts (and runs): with the neighbour-list build count, the positions and atom
  /// order a force group's forces belong to.
  long long moves;
  /// The forces of one force group on the owned atoms (3 nlocal doubles) and the drift count
  /// and neighbour-list build (neighbor->ncalls) they were computed at.
  struct GroupForces {
    std::vector<double> f;
    long long moves = -1;
    bigint build = -1;
  };
  /// For schemes whose stages name force groups (B[pair], B[bond]): the pair forces (all
  /// forces less the bonded ones) and the bonded forces.
  GroupForces pair_forces, bonded_forces;
  /// Scratch: all forces on the owned atoms, kept across a bonded evaluation.
  std::vector<double> saved_forces;
  /// The neighbour-list build (neighbor->ncalls) the colour buckets were made from, whether a
  /// sweep or F stage has used them since, and a count of the times they were made.
  bigint colour_build;
  bool colours_used;
  long long colour_epoch;
  /// The colour of each atom at that build (owned atoms of the list; 8 for the others).
  std::vector<unsigned char> atom_colour;
  /// What the pack/unpack functions move: velocities forward, velocity changes or forces back.
  enum { COMM_V, COMM_DV, COMM_F } comm_mode;

  /// Inverse masses of owned and ghost atoms; the ghost velocities the last forward
  /// communication delivered (3 nghost); the dissipative and random forces of F stages.
  std::vector<double> inv_mass, ghost_v, full;
  /// The virial of the F pair forces in `full` (xx, yy, zz, xy, xz, yz).
  double full_virial[6];
  /// Per colour, the owned atoms (in the neighbour list's order) and their listed pairs; the
  /// pairs are bucketed only when a sweep or F stage needs them (`pairs_epoch`: the
  /// `colour_epoch` they were made at).
  std::vector<int> colour_atoms[8], colour_pairs[8];
  long long pairs_epoch;
  /// Per stage (1-based; 0 unused): whether a compute asked for the velocities after it, and
  /// their local kinetic tensor at the last step.
  std::vector<char> kinetic_wanted;
  std::vector<std::array<double, 6>> kinetic_sums;
  void record(int stage);

  void run_stages(int from, int to);
  void drift(double h);
  void kick(double h, const double *forces, const double *extra);
  void sweep(const DpdSplit::Stage &stage);
  void full_force(const DpdSplit::Stage &stage, const double *forces);
  const double *forces_of(int group, bool final_positions);
  bool current(const GroupForces &g) const;
  void evaluate_bonded();
  void refresh(int eflag, int vflag);
  void refresh_ghosts();
  void check_subdomain_size();
  void check_exclusive();
  void check_cutoffs_and_tags();
  void check_special_factors();
  void check_trotter_input();
  void check_groups();
  void prepare_atoms();
  void colour_atoms_of_list();
  void colour_pairs_of_list();
  void note_evaluation();
  bool recorded() const;
  void check_status(int status, const char *what);
};

}    // namespace LAMMPS_NS

#endif
