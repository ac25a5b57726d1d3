/* fix dpd/split: one step of an exported splitting scheme of DPD per LAMMPS step.
   SPDX-License-Identifier: MIT

   The plugin only moves data: the pairwise sweeps (O, Ob) and the dissipative and random
   forces of F are computed by the dpd-lammps kernels (Rust, dpd-core's pair updates and
   Philox pair noise). A is the drift, B the kick by the forces LAMMPS computes.

   Sequential sweeps across ranks: each rank's subdomain is cut into 2 x 2 x 2 octants
   (colours); a sweep visits colour by colour, on every rank at once, the pairs whose owned
   atom i lies in that colour's octant, with ghost velocities fresh (forward communication)
   before the colour and the ghosts' velocity changes sent to their owners (reverse
   communication) after it. Two octants of one colour (on different ranks, or periodic images)
   are at least half a subdomain minus the skin apart, so when every subdomain side is at least
   4 r_c + 2 skin no atom is touched by two ranks within a colour, and the sweep is sequential
   in effect: each pair update sees the current velocities of both atoms. */

#include "fix_dpd_split.h"

#include "angle.h"
#include "atom.h"
#include "bond.h"
#include "comm.h"
#include "dihedral.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "improper.h"
#include "kspace.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;
using namespace FixConst;
using DpdSplit::Stage;

static_assert(sizeof(tagint) == sizeof(int), "the kernels take 32-bit atom tags (LAMMPS_SMALLBIG)");

namespace {

/// The names of the compiled schemes, for error messages.
std::string compiled_names()
{
  std::string names;
  for (int k = 0; k < DpdSplit::NSCHEMES; ++k) {
    if (k) names += ", ";
    names += DpdSplit::SCHEMES[k].name;
  }
  return names;
}

/// Whether a stage needs forces or pair geometry at the current positions.
bool needs_positions(int flow)
{
  return flow != DpdSplit::FLOW_A;
}

}    // namespace

FixDPDSplit::FixDPDSplit(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), scheme(nullptr), kernels(nullptr), list(nullptr), split(0),
    stale(false), epoch(0), full_epoch(-1), comm_mode(COMM_V)
{
  const char *usage = "fix ID group dpd/split SCHEME kT gamma r_c seed [exponent s]";
  if (narg != 8 && narg != 10)
    error->all(FLERR, "fix dpd/split: expected {} (5 or 7 arguments after 'fix ID group'), got {}",
               usage, narg - 3);
  for (int k = 0; k < DpdSplit::NSCHEMES; ++k) {
    const DpdSplit::Scheme &s = DpdSplit::SCHEMES[k];
    if (strcmp(arg[3], s.name) == 0 || strcmp(arg[3], s.ident) == 0) scheme = &s;
  }
  if (!scheme)
    error->all(FLERR,
               "fix dpd/split: scheme '{}' is not compiled into this plugin; compiled: {} "
               "(export it with `dpd export lammps '{}' --out DIR --build`)",
               arg[3], compiled_names(), arg[3]);
  auto number = [&](int k, const char *field) {
    char *end = nullptr;
    errno = 0;
    double value = strtod(arg[k], &end);
    if (end == arg[k] || *end != '\0' || errno != 0 || !std::isfinite(value))
      error->all(FLERR, "fix dpd/split: {} = '{}' is not a finite number ({})", field, arg[k],
                 usage);
    return value;
  };
  kt = number(4, "kT");
  gamma = number(5, "gamma");
  rc = number(6, "r_c");
  {
    char *end = nullptr;
    errno = 0;
    long long value = strtoll(arg[7], &end, 10);
    if (end == arg[7] || *end != '\0' || errno != 0 || value <= 0)
      error->all(FLERR, "fix dpd/split: seed = '{}' must be a positive integer ({})", arg[7],
                 usage);
    seed = (unsigned long long) value;
  }
  exponent = 2.0;
  if (narg == 10) {
    if (strcmp(arg[8], "exponent") != 0)
      error->all(FLERR, "fix dpd/split: unknown keyword '{}'; the only keyword is 'exponent s' ({})",
                 arg[8], usage);
    exponent = number(9, "exponent");
  }
  for (int k = 0; k < scheme->nstages; ++k)
    if (scheme->stages[k].flow == DpdSplit::FLOW_T)
      error->all(FLERR, "fix dpd/split: scheme '{}' = {} has a T stage, which this plugin does "
                 "not run", scheme->name, scheme->program);
  char message[256] = {0};
  kernels = dpd_lammps_new(gamma, kt, rc, exponent, message, sizeof(message));
  if (!kernels) error->all(FLERR, "fix dpd/split: {}", message);
  if (!scheme->consistent && comm->me == 0)
    error->warning(FLERR, "fix dpd/split: scheme '{}' = {} is inconsistent (exported with "
                   "--allow-inconsistent): it does not sample the DPD ensemble",
                   scheme->name, scheme->program);

  time_integrate = 1;
  dynamic_group_allow = 0;
  comm_forward = 3;
  comm_reverse = 3;

  // Where LAMMPS's force evaluation falls: the cyclic state of the step is found by running
  // the analysis twice, the second time starting from the staleness the step ends with.
  bool stale_at_start = false;
  for (int pass = 0; pass < 2; ++pass) {
    bool s = stale_at_start;
    split = scheme->nstages;
    for (int k = 0; k < scheme->nstages; ++k) {
      int flow = scheme->stages[k].flow;
      if (flow == DpdSplit::FLOW_A)
        s = true;
      else if (s && needs_positions(flow)) {
        split = k;
        break;
      }
    }
    s = false;
    for (int k = split; k < scheme->nstages; ++k) {
      int flow = scheme->stages[k].flow;
      if (flow == DpdSplit::FLOW_A)
        s = true;
      else if (s && needs_positions(flow))
        s = false;
    }
    stale_at_start = s;
  }
}

FixDPDSplit::~FixDPDSplit()
{
  dpd_lammps_free(kernels);
}

int FixDPDSplit::setmask()
{
  return INITIAL_INTEGRATE | FINAL_INTEGRATE;
}

void FixDPDSplit::init()
{
  if (igroup != 0)
    error->all(FLERR, "fix dpd/split: group '{}' given; the fix integrates all atoms (group all), "
               "since its pair sweeps couple every pair within r_c", group->names[igroup]);
  if (domain->triclinic)
    error->all(FLERR, "fix dpd/split: a triclinic box is not supported (orthogonal boxes only)");
  if (!atom->tag_enable)
    error->all(FLERR, "fix dpd/split: needs atom IDs (atom_modify id yes), the pair noise is keyed by them");
  if (!force->pair)
    error->all(FLERR, "fix dpd/split: needs a pair style (its neighbour list gives the pairs within r_c)");
  if (force->pair->cutforce < rc)
    error->all(FLERR, "fix dpd/split: r_c = {} exceeds the pair style's cutoff {}; the neighbour "
               "list must hold every pair within r_c", rc, force->pair->cutforce);
  if (!force->newton_pair)
    error->all(FLERR, "fix dpd/split: needs newton_pair on (each pair in one rank's list only)");
  if (update->dt <= 0.0) error->all(FLERR, "fix dpd/split: timestep must be > 0");
  for (int d = 0; d < domain->dimension; ++d) {
    if (!domain->periodicity[d] && comm->procgrid[d] == 1) continue;
    double side = domain->prd[d] / comm->procgrid[d];
    double need = 4.0 * rc + 2.0 * neighbor->skin;
    if (side < need)
      error->all(FLERR, "fix dpd/split: subdomain side {:.4g} along {} is below 4 r_c + 2 skin = "
                 "{:.4g}, the size the staged sweep needs to stay sequential; use fewer ranks "
                 "along {} (processors command) or a larger box", side, "xyz"[d], need, "xyz"[d]);
  }
  neighbor->add_request(this);
}

void FixDPDSplit::init_list(int, NeighList *ptr)
{
  list = ptr;
}

void FixDPDSplit::setup(int)
{
  stale = false;
  ++epoch;
}

void FixDPDSplit::initial_integrate(int)
{
  run_stages(0, split);
}

void FixDPDSplit::final_integrate()
{
  // LAMMPS has communicated, possibly re-neighboured, and computed forces.
  stale = false;
  ++epoch;
  run_stages(split, scheme->nstages);
  // Observables at the step's end: re-evaluate forces (and so the virial) at the final
  // positions on steps where a compute needs energy or virial.
  bigint now = update->ntimestep;
  if (stale && (update->eflag_global == now || update->vflag_global == now)) {
    int vflag = update->vflag_global == now ? (force->newton_pair ? VIRIAL_FDOTR : VIRIAL_PAIR) : 0;
    refresh(update->eflag_global == now, vflag);
  }
}

void FixDPDSplit::run_stages(int from, int to)
{
  for (int k = from; k < to; ++k) {
    const Stage &stage = scheme->stages[k];
    if (stale && needs_positions(stage.flow)) refresh(0, 0);
    double h = stage.coeff * update->dt;
    switch (stage.flow) {
      case DpdSplit::FLOW_A:
        drift(h);
        break;
      case DpdSplit::FLOW_B:
        kick(h, nullptr);
        break;
      case DpdSplit::FLOW_O:
      case DpdSplit::FLOW_OB:
        sweep(stage);
        break;
      case DpdSplit::FLOW_F:
        full_force(stage);
        break;
      default:    // T: refused in the constructor
        break;
    }
  }
}

void FixDPDSplit::drift(double h)
{
  double **x = atom->x, **v = atom->v;
  for (int i = 0; i < atom->nlocal; ++i)
    for (int d = 0; d < 3; ++d) x[i][d] += h * v[i][d];
  stale = true;
  ++epoch;
}

void FixDPDSplit::kick(double h, const double *extra)
{
  prepare_atoms();
  double **v = atom->v, **f = atom->f;
  for (int i = 0; i < atom->nlocal; ++i)
    for (int d = 0; d < 3; ++d)
      v[i][d] += h * inv_mass[i] * (f[i][d] + (extra ? extra[3 * i + d] : 0.0));
}

/// Inverse masses of owned and ghost atoms.
void FixDPDSplit::prepare_atoms()
{
  int nall = atom->nlocal + atom->nghost;
  inv_mass.resize(nall);
  for (int i = 0; i < nall; ++i)
    inv_mass[i] = 1.0 / (atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]]);
}

/// The pairs of the neighbour list, bucketed by the octant of the subdomain holding atom i.
void FixDPDSplit::colour_pairs_of_list()
{
  double **x = atom->x;
  double mid[3];
  for (int d = 0; d < 3; ++d) mid[d] = 0.5 * (domain->sublo[d] + domain->subhi[d]);
  for (auto &pairs : colour_pairs) pairs.clear();
  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    int colour = (x[i][0] >= mid[0]) | ((x[i][1] >= mid[1]) << 1) | ((x[i][2] >= mid[2]) << 2);
    std::vector<int> &pairs = colour_pairs[colour];
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; ++jj) {
      pairs.push_back(i);
      pairs.push_back(jlist[jj] & NEIGHMASK);
    }
  }
}

void FixDPDSplit::check_status(int status, const char *what)
{
  if (status != DPD_LAMMPS_OK)
    error->one(FLERR, "fix dpd/split: the kernels refused the {} (status {}): an internal "
               "inconsistency of the plugin, please report it", what, status);
}

void FixDPDSplit::sweep(const Stage &stage)
{
  prepare_atoms();
  colour_pairs_of_list();
  int flow = stage.flow == DpdSplit::FLOW_O ? DPD_LAMMPS_SWEEP_O : DPD_LAMMPS_SWEEP_OB;
  double h = stage.coeff * update->dt;
  comm_mode = COMM_V;
  comm->forward_comm(this);
  for (int c = 0; c < 8; ++c) {
    const std::vector<int> &pairs = colour_pairs[stage.reverse ? 7 - c : c];
    int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
    ghost_v.assign(&atom->v[0][0] + 3 * nlocal, &atom->v[0][0] + 3 * nall);
    check_status(dpd_lammps_sweep(kernels, flow, h, seed, (uint64_t) update->ntimestep,
                                  stage.stream, stage.reverse, pairs.size() / 2, pairs.data(),
                                  nall, &atom->x[0][0], &atom->v[0][0], inv_mass.data(),
                                  atom->tag),
                 "sweep");
    comm_mode = COMM_DV;
    comm->reverse_comm(this);
    comm_mode = COMM_V;
    comm->forward_comm(this);
  }
}

void FixDPDSplit::full_force(const Stage &stage)
{
  int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  if (full_epoch != epoch) {
    prepare_atoms();
    comm_mode = COMM_V;
    comm->forward_comm(this);
    full.assign(3 * nall, 0.0);
    colour_pairs_of_list();
    for (auto &pairs : colour_pairs)
      check_status(dpd_lammps_dissipative_random(kernels, update->dt, seed,
                                                 (uint64_t) update->ntimestep, stage.stream,
                                                 pairs.size() / 2, pairs.data(), nall,
                                                 &atom->x[0][0], &atom->v[0][0],
                                                 inv_mass.data(), atom->tag, full.data()),
                   "full force");
    comm_mode = COMM_F;
    comm->reverse_comm(this);
    full_epoch = epoch;
  }
  kick(stage.coeff * update->dt, full.data());
}

/// Forces and ghost positions at the current positions, as LAMMPS's Verlet computes them
/// between initial_integrate and final_integrate (re-neighbouring when the skin is used up).
void FixDPDSplit::refresh(int eflag, int vflag)
{
  if (neighbor->decide()) {
    domain->pbc();
    if (domain->box_change) {
      domain->reset_box();
      comm->setup();
      if (neighbor->style) neighbor->setup_bins();
    }
    comm->exchange();
    comm->borders();
    neighbor->build(1);
  } else {
    comm->forward_comm();
  }
  ++epoch;
  int nall = atom->nlocal + (force->newton ? atom->nghost : 0);
  memset(&atom->f[0][0], 0, sizeof(double) * 3 * nall);
  if (force->pair && force->pair->compute_flag) force->pair->compute(eflag, vflag);
  if (atom->molecular) {
    if (force->bond) force->bond->compute(eflag, vflag);
    if (force->angle) force->angle->compute(eflag, vflag);
    if (force->dihedral) force->dihedral->compute(eflag, vflag);
    if (force->improper) force->improper->compute(eflag, vflag);
  }
  if (force->kspace && force->kspace->compute_flag) force->kspace->compute(eflag, vflag);
  if (force->newton) comm->reverse_comm();
  stale = false;
}

int FixDPDSplit::pack_forward_comm(int n, int *list_, double *buf, int, int *)
{
  double **v = atom->v;
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) buf[3 * k + d] = v[list_[k]][d];
  return 3 * n;
}

void FixDPDSplit::unpack_forward_comm(int n, int first, double *buf)
{
  double **v = atom->v;
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) v[first + k][d] = buf[3 * k + d];
}

int FixDPDSplit::pack_reverse_comm(int n, int first, double *buf)
{
  int nlocal = atom->nlocal;
  for (int k = 0; k < n; ++k) {
    int g = first + k;
    for (int d = 0; d < 3; ++d)
      buf[3 * k + d] = comm_mode == COMM_F ? full[3 * g + d]
                                           : atom->v[g][d] - ghost_v[3 * (g - nlocal) + d];
  }
  return 3 * n;
}

void FixDPDSplit::unpack_reverse_comm(int n, int *list_, double *buf)
{
  for (int k = 0; k < n; ++k) {
    int i = list_[k];
    for (int d = 0; d < 3; ++d) {
      if (comm_mode == COMM_F)
        full[3 * i + d] += buf[3 * k + d];
      else
        atom->v[i][d] += buf[3 * k + d];
    }
  }
}
