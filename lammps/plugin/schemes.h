/* The stage tables of the schemes compiled into the plugin; `dpd export lammps` generates
   schemes.cpp from dpd-ir's programs. SPDX-License-Identifier: MIT */
#ifndef DPD_SPLIT_SCHEMES_H
#define DPD_SPLIT_SCHEMES_H

namespace DpdSplit {

/// The sub-flows of the scheme language (docs/algorithms.md section 2).
enum Flow { FLOW_A = 0, FLOW_B = 1, FLOW_O = 2, FLOW_OB = 3, FLOW_T = 4, FLOW_F = 5 };

/// The forces a B or F stage applies: all of them, or one force group of the scheme language
/// (`B[pair]`: the pair styles; `B[bond]`: the bond, angle, dihedral and improper styles).
enum Group { GROUP_ALL = 0, GROUP_PAIR = 1, GROUP_BOND = 2 };

/// One stage of a step: flow, step length `coeff * dt`, random stream, sweep order, and for B
/// and F the force group it applies.
struct Stage {
  int flow;
  double coeff;
  int stream;
  int reverse;
  int group;
};

/// An exported scheme: the name given to the exporter, its lowercase identifier (the name the
/// fix accepts besides the name itself), its program as dpd check prints it, whether the order
/// analysis found it consistent, and its stages.
struct Scheme {
  const char *name;
  const char *ident;
  const char *program;
  int consistent;
  int nstages;
  const Stage *stages;
};

extern const Scheme SCHEMES[];
extern const int NSCHEMES;

}    // namespace DpdSplit

#endif
