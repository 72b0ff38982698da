//! The Robotino's ring of infrared distance sensors: geometry and the volts-to-metres table.

use core::f32::consts::PI;

/// Number of sensors in the ring.
pub const IR_SENSOR_COUNT: usize = 9;
/// Angle between neighbouring sensors (40 degrees); sensor 0 faces forward.
pub const IR_SPACING_RAD: f32 = 40.0 * PI / 180.0;
/// Shortest distance the table covers.
pub const IR_MIN_RANGE_M: f32 = 0.04;
/// Longest distance the table covers.
pub const IR_MAX_RANGE_M: f32 = 0.41;
/// The value a sensor reports when its voltage lies outside the table.
pub const IR_NO_READING: f32 = 0.0;

/// Mounting angle of sensor `index` in the robot frame, counter-clockwise from forward.
pub fn sensor_angle_rad(index: usize) -> f32 {
    index as f32 * IR_SPACING_RAD
}

/// The vendor's calibration: (volts, metres), volts rising, distance falling. Between points
/// the distance is linear in the voltage.
const VOLTS_TO_METRES: [(f32, f32); 14] = [
    (0.30, 0.41),
    (0.39, 0.35),
    (0.41, 0.30),
    (0.50, 0.25),
    (0.75, 0.18),
    (0.80, 0.16),
    (0.95, 0.14),
    (1.05, 0.12),
    (1.30, 0.10),
    (1.40, 0.09),
    (1.55, 0.08),
    (1.80, 0.07),
    (2.35, 0.05),
    (2.55, 0.04),
];

/// Converts a sensor voltage to a distance; [`IR_NO_READING`] outside the table or for NaN.
pub fn volts_to_metres(volts: f32) -> f32 {
    let table = &VOLTS_TO_METRES;
    let (first_v, _) = table[0];
    let (last_v, _) = table[table.len() - 1];
    // The negated comparison also rejects NaN.
    if !(volts >= first_v && volts <= last_v) {
        return IR_NO_READING;
    }
    for pair in table.windows(2) {
        let (v0, d0) = pair[0];
        let (v1, d1) = pair[1];
        if volts <= v1 {
            let t = (volts - v0) / (v1 - v0);
            return d0 + t * (d1 - d0);
        }
    }
    table[table.len() - 1].1
}

/// Converts a distance back to the voltage a sensor would report, for simulation; `None`
/// when the distance lies outside the sensor's range.
pub fn metres_to_volts(distance_m: f32) -> Option<f32> {
    if !(IR_MIN_RANGE_M..=IR_MAX_RANGE_M).contains(&distance_m) {
        return None;
    }
    for pair in VOLTS_TO_METRES.windows(2) {
        let (v0, d0) = pair[0];
        let (v1, d1) = pair[1];
        if distance_m >= d1 {
            let t = (d0 - distance_m) / (d0 - d1);
            return Some(v0 + t * (v1 - v0));
        }
    }
    Some(VOLTS_TO_METRES[VOLTS_TO_METRES.len() - 1].0)
}

/// One reading of the whole ring, in metres; [`IR_NO_READING`] where a sensor saw nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IrScan {
    pub distances_m: [f32; IR_SENSOR_COUNT],
}

impl IrScan {
    /// A scan in which no sensor sees anything.
    pub const EMPTY: IrScan = IrScan {
        distances_m: [IR_NO_READING; IR_SENSOR_COUNT],
    };

    /// The nearest obstacle any sensor reports, with its sensor index.
    pub fn nearest(&self) -> Option<(usize, f32)> {
        self.distances_m
            .iter()
            .copied()
            .enumerate()
            .filter(|&(_, d)| d > IR_NO_READING)
            .fold(None, |best, (i, d)| match best {
                Some((_, bd)) if bd <= d => best,
                _ => Some((i, d)),
            })
    }

    /// The nearest obstacle among the sensors whose direction lies within `half_width_rad`
    /// of `heading_rad` (robot frame).
    pub fn nearest_towards(&self, heading_rad: f32, half_width_rad: f32) -> Option<f32> {
        self.distances_m
            .iter()
            .copied()
            .enumerate()
            .filter(|&(i, d)| {
                d > IR_NO_READING
                    && crate::wrap_angle(sensor_angle_rad(i) - heading_rad).abs() <= half_width_rad
            })
            .map(|(_, d)| d)
            .fold(None, |best: Option<f32>, d| {
                Some(best.map_or(d, |b| b.min(d)))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f32, b: f32) -> bool {
        (a - b).abs() < 1e-5
    }

    #[test]
    fn table_points_map_exactly() {
        for &(v, d) in VOLTS_TO_METRES.iter() {
            assert!(
                close(volts_to_metres(v), d),
                "{v} V -> {}",
                volts_to_metres(v)
            );
        }
    }

    #[test]
    fn interpolates_linearly_between_points() {
        // Halfway between 0.50 V (0.25 m) and 0.75 V (0.18 m).
        assert!(close(volts_to_metres(0.625), 0.215));
        // A quarter of the way from 1.05 V (0.12 m) to 1.30 V (0.10 m).
        assert!(close(volts_to_metres(1.1125), 0.115));
    }

    #[test]
    fn outside_the_table_is_no_reading() {
        assert_eq!(volts_to_metres(0.29), IR_NO_READING);
        assert_eq!(volts_to_metres(2.56), IR_NO_READING);
        assert_eq!(volts_to_metres(-1.0), IR_NO_READING);
        assert_eq!(volts_to_metres(f32::NAN), IR_NO_READING);
        assert_eq!(volts_to_metres(f32::INFINITY), IR_NO_READING);
    }

    #[test]
    fn distance_falls_as_voltage_rises() {
        let mut last = f32::INFINITY;
        let mut v = 0.30;
        while v <= 2.55 {
            let d = volts_to_metres(v);
            assert!(d <= last + 1e-6 && d > 0.0);
            last = d;
            v += 0.01;
        }
    }

    #[test]
    fn metres_to_volts_inverts_the_table() {
        let mut d = IR_MIN_RANGE_M;
        while d <= IR_MAX_RANGE_M {
            let v = metres_to_volts(d).unwrap_or(f32::NAN);
            assert!((volts_to_metres(v) - d).abs() < 1e-4, "{d} m");
            d += 0.005;
        }
        assert_eq!(metres_to_volts(0.5), None);
        assert_eq!(metres_to_volts(0.01), None);
    }

    #[test]
    fn ring_geometry() {
        assert!(close(sensor_angle_rad(0), 0.0));
        assert!(close(sensor_angle_rad(1), 40f32.to_radians()));
        assert!(close(sensor_angle_rad(8), 320f32.to_radians()));
    }

    #[test]
    fn nearest_skips_empty_sensors() {
        let mut scan = IrScan::EMPTY;
        assert_eq!(scan.nearest(), None);
        scan.distances_m[3] = 0.2;
        scan.distances_m[7] = 0.1;
        assert_eq!(scan.nearest(), Some((7, 0.1)));
        // Sensor 0 faces forward; sensors 1 and 8 are 40 degrees either side.
        scan.distances_m[8] = 0.3;
        assert_eq!(scan.nearest_towards(0.0, 0.8), Some(0.3));
        assert_eq!(scan.nearest_towards(0.0, 0.1), None);
    }
}
