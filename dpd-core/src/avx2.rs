//! Run-time dispatch to code compiled with AVX2.
//!
//! The hot loops (cell scans, pair geometry) are written once, portably, and vectorised by the
//! compiler. On x86_64 CPUs with AVX2 (detected at run time, so one binary serves every CPU)
//! they run inside a function compiled with AVX2 enabled, into which they are inlined; both
//! paths compute the same numbers, because neither contracts multiply-adds.

/// Proof that the CPU has AVX2: made only by [`Avx2::detect`], so that code holding one may
/// build AVX2 vectors ([`crate::lanes::Vector::from_fn`]) without unsafe code of its own.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
pub(crate) struct Avx2(());

#[cfg(target_arch = "x86_64")]
impl Avx2 {
    /// `Some` when the CPU has AVX2 (the detection is cached after the first call).
    #[inline(always)]
    pub(crate) fn detect() -> Option<Avx2> {
        std::arch::is_x86_feature_detected!("avx2").then_some(Avx2(()))
    }
}

/// `f()`, inside a function compiled with AVX2 when the CPU has it. `f` and what it calls
/// are compiled with AVX2 only as far as they are inlined into that function.
#[inline(always)]
pub(crate) fn with_avx2<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if Avx2::detect().is_some() {
        // SAFETY: the feature was detected.
        return unsafe { in_avx2(f) };
    }
    f()
}

/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn in_avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}
