//! Huge pages for the arrays of a very large mesh. An encode walks its corner table and
//! marks at random: past a few gigabytes every step also misses the TLB and the page tables
//! themselves no longer stay in cache. This allocator asks Linux for transparent huge pages
//! (2 MiB) on every block of 256 MiB or more (a corner table's array from about 20M
//! triangles on). Smaller blocks are left as they are: their faults cost more with huge pages
//! than their walks gain (a 2M-triangle encode was 1.3x slower with them from 32 MiB).

use std::alloc::{GlobalAlloc, Layout, System};

/// Blocks from this size on are advised.
const HUGE_MIN: usize = 256 << 20;
/// A transparent huge page.
const HUGE_PAGE: usize = 2 << 20;

/// The system allocator, with huge pages advised on large blocks.
pub struct HugePages;

/// Advises huge pages on the whole 2 MiB pages inside `[ptr, ptr + size)`.
fn advise(ptr: *mut u8, size: usize) {
    if ptr.is_null() || size < HUGE_MIN {
        return;
    }
    let start = (ptr as usize).next_multiple_of(HUGE_PAGE);
    let end = (ptr as usize + size) / HUGE_PAGE * HUGE_PAGE;
    if end > start {
        // SAFETY: the range lies inside a block this allocator just handed out; the advice
        // changes how its pages are backed, never their contents. A failure is ignored.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
}

// SAFETY: every call goes to `System`, which upholds the contract; `advise` does not touch
// the memory's contents.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let ptr = System.alloc(layout);
        advise(ptr, layout.size());
        ptr
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let ptr = System.alloc_zeroed(layout);
        advise(ptr, layout.size());
        ptr
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let new = System.realloc(ptr, layout, new_size);
        advise(new, new_size);
        new
    }
}
