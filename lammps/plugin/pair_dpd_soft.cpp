/* pair_style dpd/soft: the conservative force of DPD alone. SPDX-License-Identifier: MIT

     pair_style dpd/soft CUTOFF
     pair_coeff I J A [CUTOFF]

   The soft repulsion F = A (1 - r/r_c) e_ij for r < r_c, energy A r_c (1 - r/r_c)^2 / 2, the
   conservative part of pair dpd, without its dissipative and random forces, which fix
   dpd/split applies itself (pair dpd draws two random numbers per pair even at zero friction).
   Forces, energy and virial are computed by the dpd-lammps kernels (dpd-core's soft potential)
   over LAMMPS's half neighbour list; special-bond factors (special_bonds lj) scale each pair's
   force and energy. There is no mixing rule (as for pair dpd): every type pair needs a
   pair_coeff. Newton's third law for pairs must be on. */

#include "pair_dpd_soft.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "utils.h"

#include "dpd_lammps.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

using namespace LAMMPS_NS;

namespace {

const char *const USAGE = "pair_style dpd/soft CUTOFF; pair_coeff I J A [CUTOFF]";

/// The finite number `text` is, else a LAMMPS error naming the field, the value and the usage.
double number(Error *error, const char *text, const char *field)
{
  char *end = nullptr;
  errno = 0;
  double value = strtod(text, &end);
  if (end == text || *end != '\0' || errno != 0 || !std::isfinite(value))
    error->all(FLERR, "pair dpd/soft: {} = '{}' is not a finite number ({})", field, text, USAGE);
  return value;
}

/// `number`, required to be positive (a cutoff).
double cutoff(Error *error, const char *text)
{
  double value = number(error, text, "cutoff");
  if (value <= 0.0)
    error->all(FLERR, "pair dpd/soft: cutoff = {} must be positive ({})", value, USAGE);
  return value;
}

}    // namespace

PairDPDSoft::PairDPDSoft(LAMMPS *lmp) :
    Pair(lmp), cut_global(0.0), special{1.0, 1.0, 1.0, 1.0}, pair_record(nullptr), recorded(0)
{
  // The kernels tally the virial pair by pair; there is no single(), restart or data output.
  no_virial_fdotr_compute = 1;
  single_enable = 0;
  restartinfo = 0;
  writedata = 0;
}

PairDPDSoft::~PairDPDSoft()
{
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
}

int PairDPDSoft::slot(int i, int j) const
{
  return i * (atom->ntypes + 1) + j;
}

void PairDPDSoft::allocate()
{
  allocated = 1;
  int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  memory->create(cutsq, n, n, "pair:cutsq");
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) setflag[i][j] = 0;
  a.assign(n * n, 0.0);
  cut.assign(n * n, 0.0);
}

void PairDPDSoft::settings(int narg, char **arg)
{
  if (narg != 1)
    error->all(FLERR, "pair dpd/soft: expected 1 argument (the global cutoff), got {} ({})", narg,
               USAGE);
  cut_global = cutoff(error, arg[0]);
}

void PairDPDSoft::coeff(int narg, char **arg)
{
  if (narg != 3 && narg != 4)
    error->all(FLERR, "pair dpd/soft: pair_coeff expects I J A [CUTOFF], got {} arguments ({})",
               narg, USAGE);
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  double a_one = number(error, arg[2], "A");
  double cut_one = narg == 4 ? cutoff(error, arg[3]) : cut_global;
  int count = 0;
  for (int i = ilo; i <= ihi; ++i)
    for (int j = (jlo > i ? jlo : i); j <= jhi; ++j) {
      a[slot(i, j)] = a_one;
      cut[slot(i, j)] = cut_one;
      setflag[i][j] = 1;
      ++count;
    }
  if (count == 0)
    error->all(FLERR, "pair dpd/soft: pair_coeff {} {} names no type pair", arg[0], arg[1]);
}

void PairDPDSoft::init_style()
{
  if (!force->newton_pair)
    error->all(FLERR, "pair dpd/soft: needs newton_pair on (the kernels apply each pair's "
                      "force to both atoms, ghosts included)");
  for (int k = 0; k < 4; ++k) special[k] = force->special_lj[k];
  neighbor->add_request(this);
  // Until a fix dpd/split of this run asks again (its init() comes after this one).
  pair_record = nullptr;
}

double PairDPDSoft::init_one(int i, int j)
{
  if (!setflag[i][j])
    error->all(FLERR, "pair dpd/soft: no pair_coeff for types {} {} (there is no mixing rule, as "
                      "for pair dpd)", i, j);
  a[slot(j, i)] = a[slot(i, j)];
  cut[slot(j, i)] = cut[slot(i, j)];
  return cut[slot(i, j)];
}

void PairDPDSoft::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  int nall = atom->nlocal + atom->nghost;
  int status = dpd_lammps_soft_forces(
      atom->ntypes, a.data(), cut.data(), special, list->inum, list->ilist, list->numneigh,
      list->firstneigh, nall, nall ? atom->x[0] : nullptr, atom->type,
      nall ? atom->f[0] : nullptr, eflag_global ? &eng_vdwl : nullptr,
      vflag_global ? virial : nullptr, eflag_atom ? eatom : nullptr,
      vflag_atom && nall ? vatom[0] : nullptr, pair_record);
  if (status != DPD_LAMMPS_OK)
    error->one(FLERR, "pair dpd/soft: the kernels refused the neighbour list (status {}: {})",
               status,
               status == DPD_LAMMPS_NULL ? "a missing array" : "an atom index or type out of range");
  if (pair_record) ++recorded;
}
