//! Software prefetch of memory that is about to be read: for walks over a large model
//! whose parts lie in separate allocations (the hardware prefetcher follows strides,
//! not pointers).

/// Asks the processor to bring the bytes of `items` into the cache (a hint: it never
/// faults and changes nothing; a no-op where there is no prefetch instruction).
#[inline(always)]
pub(crate) fn prefetch_slice<T>(items: &[T]) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let start = items.as_ptr() as *const i8;
        let bytes = std::mem::size_of_val(items);
        let mut offset = 0;
        while offset < bytes {
            // SAFETY: a prefetch reads nothing the program sees and never faults, for
            // any address; SSE is part of every x86-64 processor.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(offset)) };
            offset += 64;
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = items;
}
