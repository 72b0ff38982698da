//! The floating-point functions the math builtins call.
//!
//! CLIPS 6.30 calls the C library's `log`, `sin`, `pow`, ...; the `libm` crate (a port of
//! musl's) now and then lands one ulp away from glibc's, which shows in the 15th digit
//! CLIPS prints: `(log 2.616906004615899)` is 0.961992705675572 in CLIPS and was
//! ...571 with the crate. With the `clib-math` feature (hosts, which link the C library
//! anyway) these are the C library's own functions, the ones CLIPS runs with; without
//! it (the agent image) the crate's. `sqrt`, `ceil` and `trunc` are exact in both and
//! stay the crate's.

#[cfg(feature = "clib-math")]
mod c {
    #[link(name = "m")]
    extern "C" {
        pub fn log(x: f64) -> f64;
        pub fn log10(x: f64) -> f64;
        pub fn exp(x: f64) -> f64;
        pub fn pow(x: f64, y: f64) -> f64;
        pub fn sin(x: f64) -> f64;
        pub fn cos(x: f64) -> f64;
        pub fn asin(x: f64) -> f64;
        pub fn acos(x: f64) -> f64;
        pub fn atan(x: f64) -> f64;
        pub fn sinh(x: f64) -> f64;
        pub fn cosh(x: f64) -> f64;
        pub fn tanh(x: f64) -> f64;
    }
}

macro_rules! unary {
    ($($f:ident),*) => {$(
        #[cfg(feature = "clib-math")]
        pub fn $f(x: f64) -> f64 {
            // SAFETY: the C library's function of that name takes a double by value
            // and returns one; it touches no memory of ours (only `errno`, which
            // nothing here reads), so any argument is sound.
            unsafe { c::$f(x) }
        }
        #[cfg(not(feature = "clib-math"))]
        pub use libm::$f;
    )*};
}

unary!(log, log10, exp, sin, cos, asin, acos, atan, sinh, cosh, tanh);

#[cfg(feature = "clib-math")]
pub fn pow(x: f64, y: f64) -> f64 {
    // SAFETY: as for the functions above: two doubles by value in, one out, no
    // memory of ours touched.
    unsafe { c::pow(x, y) }
}
#[cfg(not(feature = "clib-math"))]
pub use libm::pow;
