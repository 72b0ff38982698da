//! The memory functions the prebuilt `core` and compiler-generated code call. On a libc
//! target they come from libc; this image has none. The crate is `#![no_builtins]`, so
//! these loops are not turned back into calls to themselves.
//!
//! Simple byte loops: the image copies little, and correctness is easy to see.

/// # Safety
/// `dest` and `src` must be valid for `n` bytes and must not overlap.
#[no_mangle]
pub unsafe extern "C" fn memcpy(dest: *mut u8, src: *const u8, n: usize) -> *mut u8 {
    let mut i = 0;
    while i < n {
        // SAFETY: `i < n`, and the caller guarantees both ranges are valid for `n` bytes.
        unsafe { *dest.add(i) = *src.add(i) };
        i += 1;
    }
    dest
}

/// # Safety
/// `dest` and `src` must be valid for `n` bytes; they may overlap.
#[no_mangle]
pub unsafe extern "C" fn memmove(dest: *mut u8, src: *const u8, n: usize) -> *mut u8 {
    if (dest as usize) <= (src as usize) {
        // Copying upwards never overwrites a source byte before it is read.
        let mut i = 0;
        while i < n {
            // SAFETY: `i < n`, both ranges valid for `n` bytes (caller).
            unsafe { *dest.add(i) = *src.add(i) };
            i += 1;
        }
    } else {
        // Destination above the source: copy downwards for the same reason.
        let mut i = n;
        while i > 0 {
            i -= 1;
            // SAFETY: `i < n`, both ranges valid for `n` bytes (caller).
            unsafe { *dest.add(i) = *src.add(i) };
        }
    }
    dest
}

/// # Safety
/// `dest` must be valid for writes of `n` bytes.
#[no_mangle]
pub unsafe extern "C" fn memset(dest: *mut u8, value: i32, n: usize) -> *mut u8 {
    let byte = value as u8;
    let mut i = 0;
    while i < n {
        // SAFETY: `i < n`, `dest` valid for `n` bytes (caller).
        unsafe { *dest.add(i) = byte };
        i += 1;
    }
    dest
}

/// # Safety
/// `a` and `b` must be valid for reads of `n` bytes.
#[no_mangle]
pub unsafe extern "C" fn memcmp(a: *const u8, b: *const u8, n: usize) -> i32 {
    let mut i = 0;
    while i < n {
        // SAFETY: `i < n`, both ranges valid for `n` bytes (caller).
        let (x, y) = unsafe { (*a.add(i), *b.add(i)) };
        if x != y {
            return i32::from(x) - i32::from(y);
        }
        i += 1;
    }
    0
}

/// Like `memcmp`, but only zero / non-zero matters.
///
/// # Safety
/// `a` and `b` must be valid for reads of `n` bytes.
#[no_mangle]
pub unsafe extern "C" fn bcmp(a: *const u8, b: *const u8, n: usize) -> i32 {
    // SAFETY: same contract as `memcmp`.
    unsafe { memcmp(a, b, n) }
}
