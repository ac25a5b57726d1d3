/* The C ABI of the dpd-lammps kernels (lammps/kernels/src/lib.rs and soft.rs), the one
   implementation of the pair physics the plugin uses. SPDX-License-Identifier: MIT */
#ifndef DPD_LAMMPS_H
#define DPD_LAMMPS_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { DPD_LAMMPS_OK = 0, DPD_LAMMPS_NULL = 1, DPD_LAMMPS_INDEX = 2, DPD_LAMMPS_FLOW = 3,
       DPD_LAMMPS_TAG = 4, DPD_LAMMPS_STYLE = 5, DPD_LAMMPS_TYPE = 6 };
enum { DPD_LAMMPS_SWEEP_O = 0, DPD_LAMMPS_SWEEP_OB = 1, DPD_LAMMPS_SWEEP_T = 2 };

typedef struct DpdLammpsKernels DpdLammpsKernels;
/* The pairs within the sweeps' cutoff that a dpd/soft evaluation found, by colour of their
   atom i, for the sweeps that follow at the same positions (lammps/kernels/src/record.rs). */
typedef struct DpdLammpsRecord DpdLammpsRecord;

/* Per type-pair tables (gamma, rc; dpd/soft's a, rc) hold (ntypes + 1)^2 doubles at
   I * (ntypes + 1) + J; tags are LAMMPS's tagint, tag_bytes = sizeof(tagint). */
DpdLammpsKernels *dpd_lammps_new(double kbt, double exponent, int ntypes, const double *gamma,
                                 const double *rc, char *message, size_t message_len);
void dpd_lammps_free(DpdLammpsKernels *kernels);
int dpd_lammps_sweep(const DpdLammpsKernels *kernels, int flow, double h, uint64_t seed,
                     uint64_t step, int stream, int reverse, size_t npairs, const int *pairs,
                     size_t natoms, const double *x, double *v, const double *inv_mass,
                     const void *tag, int tag_bytes, const int *type, const double *soft_a,
                     const double *soft_rc, double *virial);
int dpd_lammps_sweep_recorded(const DpdLammpsKernels *kernels, int flow, double h, uint64_t seed,
                              uint64_t step, int stream, int reverse, int colour,
                              const DpdLammpsRecord *record, size_t natoms,
                              const double *x, double *v, const double *inv_mass,
                              const void *tag, int tag_bytes, const int *type,
                              const double *soft_a, const double *soft_rc, double *virial);
int dpd_lammps_dissipative_random(const DpdLammpsKernels *kernels, double dt, uint64_t seed,
                                  uint64_t step, int stream, size_t npairs, const int *pairs,
                                  size_t natoms, const double *x, const double *v,
                                  const double *inv_mass, const void *tag, int tag_bytes,
                                  const int *type, double *f, double *virial);
int dpd_lammps_soft_forces(int ntypes, const double *a, const double *rc, const double *special,
                           int inum, const int *ilist, const int *numneigh,
                           const int *const *firstneigh, int nall, const double *x,
                           const int *type, double *f, double *energy, double *virial,
                           double *eatom, double *vatom, DpdLammpsRecord *record);
DpdLammpsRecord *dpd_lammps_record_new(const DpdLammpsKernels *kernels);
int dpd_lammps_record_colours(DpdLammpsRecord *record, size_t natoms, const unsigned char *colour);
void dpd_lammps_record_free(DpdLammpsRecord *record);

#ifdef __cplusplus
}
#endif
#endif
