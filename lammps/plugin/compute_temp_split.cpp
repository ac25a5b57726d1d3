/* compute temp/split: the kinetic temperature of the velocities at a chosen point inside the
   step of fix dpd/split. SPDX-License-Identifier: MIT

     compute ID all temp/split FIX_ID [stage K]

   The velocities after stage K of the fix's scheme (1-based, in the order `dpd export lammps`
   prints the program; default: after the last O, Ob or T stage, where the scheme's thermostat
   leaves them, or at the step's end for a scheme without one), which the fix records during
   the step. Degrees of freedom as compute temp counts them (3 N less 3 for the total momentum
   and what fixes remove). A temperature compute: usable in thermo_modify temp and compute
   pressure. */

#include "compute_temp_split.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "fix_dpd_split.h"
#include "force.h"
#include "group.h"
#include "modify.h"
#include "update.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>

using namespace LAMMPS_NS;

namespace {
const char *const USAGE = "compute ID all temp/split FIX_ID [stage K]";
}

ComputeTempSplit::ComputeTempSplit(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), stage(0), fix(nullptr), tfactor(0.0)
{
  if (narg != 4 && narg != 6)
    error->all(FLERR, "compute temp/split: expected {} (1 or 3 arguments after 'compute ID "
               "group'), got {}", USAGE, narg - 3);
  fix_id = arg[3];
  if (narg == 6) {
    if (strcmp(arg[4], "stage") != 0)
      error->all(FLERR, "compute temp/split: unknown keyword '{}'; the only keyword is 'stage K' "
                 "({})", arg[4], USAGE);
    char *end = nullptr;
    errno = 0;
    long value = strtol(arg[5], &end, 10);
    if (end == arg[5] || *end != '\0' || errno != 0 || value < 1)
      error->all(FLERR, "compute temp/split: stage = '{}' must be a positive integer ({})", arg[5],
                 USAGE);
    stage = (int) value;
  }
  scalar_flag = vector_flag = 1;
  size_vector = 6;
  extscalar = 0;
  extvector = 1;
  tempflag = 1;
  vector = new double[size_vector];
}

ComputeTempSplit::~ComputeTempSplit()
{
  delete[] vector;
}

void ComputeTempSplit::init()
{
  if (igroup != 0)
    error->all(FLERR, "compute temp/split: group '{}' given; fix dpd/split records the "
               "velocities of all atoms (group all)", group->names[igroup]);
  fix = dynamic_cast<FixDPDSplit *>(modify->get_fix_by_id(fix_id));
  if (!fix)
    error->all(FLERR, "compute temp/split: '{}' is not the ID of a fix dpd/split ({})", fix_id,
               USAGE);
  int n = fix->stage_count();
  if (stage > n)
    error->all(FLERR, "compute temp/split: stage {} beyond the {} stages of fix {}'s scheme {}",
               stage, n, fix_id, fix->program());
  fix->record_kinetic(stage ? stage : fix->thermostat_stage());
}

void ComputeTempSplit::setup()
{
  dof_compute();
}

void ComputeTempSplit::dof_compute()
{
  adjust_dof_fix();
  natoms_temp = group->count(igroup);
  dof = domain->dimension * natoms_temp;
  dof -= extra_dof + fix_dof;
  tfactor = dof > 0.0 ? force->mvv2e / (dof * force->boltz) : 0.0;
}

double ComputeTempSplit::compute_scalar()
{
  invoked_scalar = update->ntimestep;
  const double *local = fix->kinetic(stage ? stage : fix->thermostat_stage());
  double twice_ke = local[0] + local[1] + local[2];
  MPI_Allreduce(&twice_ke, &scalar, 1, MPI_DOUBLE, MPI_SUM, world);
  if (dof < 0.0 && natoms_temp > 0.0)
    error->all(FLERR, "compute temp/split: temperature with negative degrees of freedom");
  scalar *= tfactor;
  return scalar;
}

void ComputeTempSplit::compute_vector()
{
  invoked_vector = update->ntimestep;
  const double *local = fix->kinetic(stage ? stage : fix->thermostat_stage());
  MPI_Allreduce(local, vector, 6, MPI_DOUBLE, MPI_SUM, world);
  for (int k = 0; k < 6; ++k) vector[k] *= force->mvv2e;
}
