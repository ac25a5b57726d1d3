//! A slice that several threads write at once, each at indices no other thread touches: the
//! one aliasing type of the crate. Only code that can prove the indices disjoint hands out its
//! elements: the pair engine ([`crate::pairs`]) for the two particles of a pair, and the
//! binning of [`crate::neighbour`] for the slots of a counting sort.

use std::marker::PhantomData;

/// A slice written concurrently at disjoint indices.
///
/// Safety contract of [`Disjoint::get`]: no two threads access the same index at the same
/// time. The pair engine guarantees it for the two particles of a pair, because
/// concurrently visited runs own pairs of disjoint particle sets.
pub(crate) struct Disjoint<'a, T> {
    ptr: *mut T,
    len: usize,
    _slice: PhantomData<&'a mut [T]>,
}

unsafe impl<T: Send> Sync for Disjoint<'_, T> {}

// A copy is one more handle to the same slice, as a shared reference to it would be; the
// contract of `get` is the same for every handle.
impl<T> Clone for Disjoint<'_, T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for Disjoint<'_, T> {}

impl<'a, T> Disjoint<'a, T> {
    pub(crate) fn new(slice: &'a mut [T]) -> Self {
        Disjoint {
            ptr: slice.as_mut_ptr(),
            len: slice.len(),
            _slice: PhantomData,
        }
    }

    /// # Safety
    /// No other reference to element `i` may be alive while the returned one is.
    #[inline(always)]
    pub(crate) unsafe fn get(self, i: usize) -> &'a mut T {
        assert!(i < self.len, "index {i} out of bounds ({})", self.len);
        // SAFETY: in bounds (checked above); exclusivity is the caller's contract.
        unsafe { &mut *self.ptr.add(i) }
    }

    /// [`Disjoint::get`] without the bounds check.
    ///
    /// # Safety
    /// As for [`Disjoint::get`], and `i` must be below the length (for the pair engine: `self`
    /// comes from `Bound::write` with the bound of the table whose pair holds `i`).
    #[inline(always)]
    pub(crate) unsafe fn get_paired(self, i: u32) -> &'a mut T {
        debug_assert!((i as usize) < self.len);
        // SAFETY: in bounds and exclusive, the caller's contract.
        unsafe { &mut *self.ptr.add(i as usize) }
    }
}
