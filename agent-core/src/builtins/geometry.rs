//! Geometry builtins for agents that weigh travel cost (beyond CLIPS; rule bases that
//! use them run in real CLIPS with the deffunction stand-ins in `rules/clips/`).
//!
//! - `(distance x1 y1 x2 y2)`: Euclidean distance in metres. Computed with CLIPS's own
//!   arithmetic steps (integer differences stay integers, then `sqrt`), so it prints
//!   the same digits as the stand-in deffunction
//!   `(sqrt (+ (* (- ?x2 ?x1) (- ?x2 ?x1)) (* (- ?y2 ?y1) (- ?y2 ?y1))))`.
//! - `(heading x1 y1 x2 y2)`: direction from the first point to the second, radians in
//!   (-pi, pi], `atan2(dy, dx)`.
//! - `(pose-compose x1 y1 th1 x2 y2 th2)`: the pose `(x y th)` reached by applying the
//!   relative pose 2 in the frame of pose 1 (SE(2) composition, nalgebra `Isometry2`);
//!   th normalised to (-pi, pi].
//! - `(pose-inverse x y th)`: the inverse SE(2) transform as `(x y th)`.
//! - `(normalize-angle a)`: `a` wrapped to (-pi, pi].

use nalgebra::{Isometry2, Vector2};

use super::math::{num_arg, T_NUMBER};
use super::{Args, Builtin, Num};
use crate::engine::Core;
use crate::error::EvalError;
use crate::value::Value;

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("distance", 4, 4, distance).quiet(),
    Builtin::eager("heading", 4, 4, heading).quiet(),
    Builtin::eager("pose-compose", 6, 6, pose_compose).quiet(),
    Builtin::eager("pose-inverse", 3, 3, pose_inverse).quiet(),
    Builtin::eager("normalize-angle", 1, 1, normalize_angle).quiet(),
];
pub const TABLE: super::Table = super::Table::new(FUNCS);

/// CLIPS `-`: integers stay integers (wrapping like CLIPS's `long long`), else floats.
fn sub(p: Num, q: Num) -> Num {
    match (p, q) {
        (Num::Int(a), Num::Int(b)) => Num::Int(a.wrapping_sub(b)),
        (a, b) => Num::Float(a.as_f64() - b.as_f64()),
    }
}

fn mul(p: Num, q: Num) -> Num {
    match (p, q) {
        (Num::Int(a), Num::Int(b)) => Num::Int(a.wrapping_mul(b)),
        (a, b) => Num::Float(a.as_f64() * b.as_f64()),
    }
}

fn add(p: Num, q: Num) -> Num {
    match (p, q) {
        (Num::Int(a), Num::Int(b)) => Num::Int(a.wrapping_add(b)),
        (a, b) => Num::Float(a.as_f64() + b.as_f64()),
    }
}

/// `n` float arguments (CLIPS's "integer or float" type error otherwise).
fn floats<const N: usize>(
    cx: &Core<'_>,
    a: Args,
    func: &'static str,
) -> Result<[f64; N], EvalError> {
    let mut out = [0.0; N];
    for (i, o) in out.iter_mut().enumerate() {
        *o = num_arg(cx, a, i, func)?.as_f64();
    }
    Ok(out)
}

fn distance(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let x1 = num_arg(cx, a, 0, "distance")?;
    let y1 = num_arg(cx, a, 1, "distance")?;
    let x2 = num_arg(cx, a, 2, "distance")?;
    let y2 = num_arg(cx, a, 3, "distance")?;
    let (dx, dy) = (sub(x2, x1), sub(y2, y1));
    let sq = add(mul(dx, dx), mul(dy, dy)).as_f64();
    Ok(Value::Float(libm::sqrt(sq)))
}

fn heading(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let [x1, y1, x2, y2] = floats::<4>(cx, a, "heading")?;
    Ok(Value::Float(libm::atan2(y2 - y1, x2 - x1)))
}

fn isometry(x: f64, y: f64, th: f64) -> Isometry2<f64> {
    Isometry2::new(Vector2::new(x, y), th)
}

/// A pose as the multifield `(x y th)`.
fn pose_value(cx: &mut Core<'_>, p: &Isometry2<f64>) -> Result<Value, EvalError> {
    let t = p.translation.vector;
    Ok(cx.make_multi(&[
        Value::Float(t.x),
        Value::Float(t.y),
        Value::Float(p.rotation.angle()),
    ])?)
}

fn pose_compose(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let [x1, y1, th1, x2, y2, th2] = floats::<6>(cx, a, "pose-compose")?;
    let p = isometry(x1, y1, th1) * isometry(x2, y2, th2);
    pose_value(cx, &p)
}

fn pose_inverse(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let [x, y, th] = floats::<3>(cx, a, "pose-inverse")?;
    let p = isometry(x, y, th).inverse();
    pose_value(cx, &p)
}

fn normalize_angle(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let [th] = floats::<1>(cx, a, "normalize-angle")?;
    if !th.is_finite() {
        return Err(EvalError::wrong_type("normalize-angle", 1, T_NUMBER));
    }
    Ok(Value::Float(nalgebra::UnitComplex::new(th).angle()))
}

// the tests evaluate builtins, whose code only `parser` links (`builtins::BUILTINS`)
#[cfg(all(test, feature = "parser"))]
mod tests {
    extern crate std;
    use crate::testutil::eval_to_string;
    use core::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

    fn num(expr: &str) -> f64 {
        let s = eval_to_string(expr);
        s.parse().unwrap_or_else(|_| panic!("{expr} printed {s:?}"))
    }

    /// The elements of a printed multifield `(a b c)` as floats.
    fn nums(expr: &str) -> std::vec::Vec<f64> {
        let s = eval_to_string(expr);
        let inner = s.trim_start_matches('(').trim_end_matches(')');
        inner
            .split(' ')
            .map(|t| t.parse().unwrap_or_else(|_| panic!("{expr} printed {s:?}")))
            .collect()
    }

    fn close(got: f64, want: f64) {
        assert!((got - want).abs() < 1e-9, "got {got}, want {want}");
    }

    #[test]
    fn distance_matches_the_clips_stand_in() {
        // printed by CLIPS 6.30 for the deffunction in rules/clips/stubs.clp
        assert_eq!(eval_to_string("(distance 0 0 3 4)"), "5.0");
        assert_eq!(eval_to_string("(distance 1 1 1 1)"), "0.0");
        close(num("(distance 1.5 2.25 -3.1 4.7)"), 5.21176553578535);
        close(num("(distance 0.1 0.2 0.3 0.4)"), 0.282842712474619);
        close(num("(distance 4.92 1.08 -3.55 6.71)"), 10.1704375520427);
        assert!(eval_to_string("(distance 0 0 a 1)").contains("#3 to be of type integer or float"));
    }

    #[test]
    fn heading_is_atan2() {
        close(num("(heading 0 0 1 0)"), 0.0);
        close(num("(heading 0 0 0 2)"), FRAC_PI_2);
        close(num("(heading 1 1 2 2)"), FRAC_PI_4);
        close(num("(heading 0 0 -1 0)"), PI);
        close(num("(heading 0 0 0 -1)"), -FRAC_PI_2);
    }

    #[test]
    fn pose_composition() {
        // identity
        let p = nums("(pose-compose 1 2 0.5 0 0 0)");
        close(p[0], 1.0);
        close(p[1], 2.0);
        close(p[2], 0.5);
        // robot at (1, 2) facing +y, 1 m ahead, then turn 90 degrees: (1, 3) facing -x
        let p = nums(&std::format!(
            "(pose-compose 1 2 {FRAC_PI_2} 1 0 {FRAC_PI_2})"
        ));
        close(p[0], 1.0);
        close(p[1], 3.0);
        close(p[2], PI);
        // angles wrap into (-pi, pi]
        let p = nums("(pose-compose 0 0 3 0 0 1)");
        close(p[2], 4.0 - 2.0 * PI);
        // composing with the inverse gives the identity
        let inv = nums("(pose-inverse 2 -1 0.7)");
        let back = nums(&std::format!(
            "(pose-compose 2 -1 0.7 {} {} {})",
            inv[0],
            inv[1],
            inv[2]
        ));
        for v in back {
            close(v, 0.0);
        }
        close(num("(normalize-angle 7)"), 7.0 - 2.0 * PI);
        close(num("(normalize-angle -4)"), 2.0 * PI - 4.0);
    }
}
