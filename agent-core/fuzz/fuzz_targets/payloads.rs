//! Every iceoryx2 payload of host-shim (`shim::payloads`) built from arbitrary bytes, as
//! a corrupt or hostile publisher could lay them out in shared memory, then decoded.
//! The decoders must not panic; whatever they accept must be in range, and decoding
//! is stable: `decode(encode(decode(p))) == decode(p)`.
#![no_main]

use core::mem::size_of;

use host_shim::shim::payloads::*;
use libfuzzer_sys::fuzz_target;

/// Builds a payload from the first `size_of::<T>()` bytes (zero-padded).
///
/// Only for the payload types below: each is `#[repr(C)]` and made of `u32`, `f32` and
/// `u8` fields (arrays included) with no padding, so every bit pattern is a valid value.
fn from_bytes<T: Copy>(data: &[u8]) -> T {
    let mut buf = [0u8; 4096];
    assert!(size_of::<T>() <= buf.len());
    let n = data.len().min(size_of::<T>());
    buf[..n].copy_from_slice(&data[..n]);
    // SAFETY: `buf` holds at least size_of::<T>() initialised bytes, `read_unaligned`
    // has no alignment requirement, and T is one of the plain-data payloads listed
    // above, for which any byte pattern is a valid value.
    unsafe { core::ptr::read_unaligned(buf.as_ptr() as *const T) }
}

fn check<T: Copy, V: PartialEq + core::fmt::Debug>(
    p: T,
    decode: impl Fn(&T) -> Result<V, DecodeError>,
    encode: impl Fn(&V) -> T,
) -> Option<V> {
    let v = decode(&p).ok()?;
    let again = decode(&encode(&v));
    assert_eq!(again.as_ref(), Ok(&v), "decode is not stable");
    Some(v)
}

fn in_range(x: f32, lo: f32, hi: f32) -> bool {
    x.is_finite() && (lo..=hi).contains(&x)
}

fuzz_target!(|data: &[u8]| {
    let Some((&kind, rest)) = data.split_first() else {
        return;
    };
    let seq = 7;
    match kind % 13 {
        0 => {
            if let Some(scan) = check(
                from_bytes::<IrScanPayload>(rest),
                |p| p.decode(),
                |v| IrScanPayload::encode(seq, v),
            ) {
                assert!(scan.distances_m.iter().all(|d| d.is_finite() && *d >= 0.0));
            }
        }
        1 => {
            check(
                from_bytes::<BumperPayload>(rest),
                |p| p.decode(),
                |v| BumperPayload::encode(seq, *v),
            );
        }
        2 => {
            if let Some(g) = check(
                from_bytes::<GyroPayload>(rest),
                |p| p.decode(),
                |v| GyroPayload::encode(seq, *v),
            ) {
                assert!(in_range(
                    g.rate_rad_s,
                    -MAX_GYRO_RATE_RAD_S,
                    MAX_GYRO_RATE_RAD_S
                ));
                assert!(g.angle_rad.is_finite());
            }
        }
        3 => {
            if let Some(o) = check(
                from_bytes::<OdometryPayload>(rest),
                |p| p.decode(),
                |v| OdometryPayload::encode(seq, v),
            ) {
                assert!(o.pose.x_m.is_finite() && o.pose.y_m.is_finite());
                assert!(o
                    .measured
                    .rpm
                    .iter()
                    .all(|r| in_range(*r, -MAX_WIRE_RPM, MAX_WIRE_RPM)));
            }
        }
        4 => {
            let p = from_bytes::<MotorCommandPayload>(rest);
            if let Some(w) = check(
                p,
                |p| p.decode(),
                |v| MotorCommandPayload::encode(seq, p.bumper_seq, *v),
            ) {
                assert!(w
                    .rpm
                    .iter()
                    .all(|r| in_range(*r, -MAX_WIRE_RPM, MAX_WIRE_RPM)));
            }
        }
        5 => {
            check(
                from_bytes::<LightPayload>(rest),
                |p| p.decode(),
                |v| LightPayload::encode(seq, *v),
            );
        }
        6 => {
            check(
                from_bytes::<PuckPayload>(rest),
                |p| p.decode(),
                |v| PuckPayload::encode(seq, *v),
            );
        }
        7 => {
            if let Some((robot, _)) = check(
                from_bytes::<SkillRequestPayload>(rest),
                |p| p.decode(),
                |(r, q)| SkillRequestPayload::encode(seq, *r, *q),
            ) {
                assert!((1..=MAX_ROBOTS).contains(&robot));
            }
        }
        8 => {
            if let Some(s) = check(
                from_bytes::<SkillStatusPayload>(rest),
                |p| p.decode(),
                |v| SkillStatusPayload::encode(seq, v),
            ) {
                assert!((1..=MAX_ROBOTS).contains(&s.robot));
            }
        }
        9 => {
            check(
                from_bytes::<HeartbeatPayload>(rest),
                |p| p.decode(),
                |(d, c)| HeartbeatPayload::encode(seq, *c, *d),
            );
        }
        10 => {
            // Text: the floats of re-encoded JSON may differ in the last digit, and
            // escapes may change the length, so stability is checked on the rest.
            if let Ok((robot, cycle, msgs)) = from_bytes::<TeamBatchPayload>(rest).decode() {
                assert!((1..=MAX_ROBOTS).contains(&robot));
                assert!(msgs.iter().all(|m| m.from == robot));
                if let Some(again) = TeamBatchPayload::encode(seq, robot, cycle, &msgs) {
                    let (r2, c2, m2) = again.decode().unwrap_or_else(|e| panic!("{e}"));
                    assert_eq!((r2, c2, m2.len()), (robot, cycle, msgs.len()));
                    for (a, b) in msgs.iter().zip(&m2) {
                        assert_eq!(
                            (a.seq, &a.kind, &a.resource, &a.data),
                            (b.seq, &b.kind, &b.resource, &b.data)
                        );
                    }
                }
            }
        }
        _ => {
            // a payload of one type read as another (a mixed-up service name)
            let p = from_bytes::<SkillStatusPayload>(rest);
            let _ = from_bytes::<MotorCommandPayload>(rest).decode();
            let _ = p.decode();
        }
    }
});
