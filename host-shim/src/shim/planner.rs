//! Path planning on the field: A* over a coarse occupancy grid in which the machines are
//! squares grown by the robot's radius, then shortened to the waypoints that line of sight
//! needs. Pure; a plan costs well under a millisecond.

use hal::field::{clearance, is_blocked, FIELD_SIZE_M};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Grid cell size: fine enough for the 15 cm lanes between machine rows.
const CELL_M: f32 = 0.0625;
const N: usize = (FIELD_SIZE_M / CELL_M) as usize;

fn cell_of(v: f32) -> usize {
    ((v / CELL_M) as isize).clamp(0, N as isize - 1) as usize
}

fn centre(c: usize) -> f32 {
    (c as f32 + 0.5) * CELL_M
}

/// A round obstacle the field does not know of: another robot, seen by the IR ring
/// (centre x, y and radius, metres).
pub type Disc = (f32, f32, f32);

/// The field's obstacles and the discs.
fn blocked_by(x: f32, y: f32, clearance_m: f32, discs: &[Disc]) -> bool {
    is_blocked(x, y, clearance_m)
        || discs
            .iter()
            .any(|&(cx, cy, r)| (x - cx).hypot(y - cy) < r + clearance_m)
}

/// Distance from a point to the nearest wall, machine footprint or disc.
pub fn clearance_of(p: (f32, f32), discs: &[Disc]) -> f32 {
    discs
        .iter()
        .map(|&(cx, cy, r)| (p.0 - cx).hypot(p.1 - cy) - r)
        .fold(clearance(p.0, p.1, None), f32::min)
}

/// True when a straight segment keeps `clearance_m` from every obstacle.
pub fn segment_is_free(a: (f32, f32), b: (f32, f32), clearance_m: f32) -> bool {
    segment_is_free_of(a, b, clearance_m, &[])
}

/// [`segment_is_free`], also clear of `discs`.
pub fn segment_is_free_of(a: (f32, f32), b: (f32, f32), clearance_m: f32, discs: &[Disc]) -> bool {
    let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    let steps = (len / 0.02).ceil().max(1.0) as usize;
    (0..=steps).all(|i| {
        let t = i as f32 / steps as f32;
        !blocked_by(
            a.0 + t * (b.0 - a.0),
            a.1 + t * (b.1 - a.1),
            clearance_m,
            discs,
        )
    })
}

/// Waypoints from `from` to `to` (excluding `from`, ending exactly at `to`), or `None` when
/// no path keeps `clearance_m`. Start and goal cells are allowed even when they touch an
/// obstacle (the robot may stand close to a machine it works at).
pub fn plan(from: (f32, f32), to: (f32, f32), clearance_m: f32) -> Option<Vec<(f32, f32)>> {
    plan_around(from, to, clearance_m, &[])
}

/// [`plan`] around `discs` too (robots in the way).
pub fn plan_around(
    from: (f32, f32),
    to: (f32, f32),
    clearance_m: f32,
    discs: &[Disc],
) -> Option<Vec<(f32, f32)>> {
    if segment_is_free_of(from, to, clearance_m, discs) {
        return Some(vec![to]);
    }
    let start = (cell_of(from.0), cell_of(from.1));
    let goal = (cell_of(to.0), cell_of(to.1));
    let idx = |c: (usize, usize)| c.1 * N + c.0;
    let free = |c: (usize, usize)| {
        c == start || c == goal || !blocked_by(centre(c.0), centre(c.1), clearance_m, discs)
    };
    // Costs in millimetres so the heap orders integers.
    let h = |c: (usize, usize)| {
        let dx = c.0.abs_diff(goal.0) as u32;
        let dy = c.1.abs_diff(goal.1) as u32;
        let (lo, hi) = (dx.min(dy), dx.max(dy));
        (hi - lo) * 63 + lo * 88
    };
    let mut cost = vec![u32::MAX; N * N];
    let mut parent = vec![usize::MAX; N * N];
    let mut open = BinaryHeap::new();
    cost[idx(start)] = 0;
    open.push(Reverse((h(start), start)));
    while let Some(Reverse((_, c))) = open.pop() {
        if c == goal {
            break;
        }
        let base = cost[idx(c)];
        for (dx, dy) in [
            (-1i32, 0i32),
            (1, 0),
            (0, -1),
            (0, 1),
            (-1, -1),
            (-1, 1),
            (1, -1),
            (1, 1),
        ] {
            let nx = c.0 as i32 + dx;
            let ny = c.1 as i32 + dy;
            if nx < 0 || ny < 0 || nx >= N as i32 || ny >= N as i32 {
                continue;
            }
            let n = (nx as usize, ny as usize);
            // A diagonal step must not cut an obstacle's corner.
            let corner_free = dx == 0 || dy == 0 || (free((n.0, c.1)) && free((c.0, n.1)));
            if !free(n) || !corner_free {
                continue;
            }
            let step = if dx != 0 && dy != 0 { 88 } else { 63 };
            let new_cost = base + step;
            if new_cost < cost[idx(n)] {
                cost[idx(n)] = new_cost;
                parent[idx(n)] = idx(c);
                open.push(Reverse((new_cost + h(n), n)));
            }
        }
    }
    if cost[idx(goal)] == u32::MAX {
        return None;
    }
    let mut cells = vec![goal];
    let mut at = idx(goal);
    while at != idx(start) {
        at = parent[at];
        cells.push((at % N, at / N));
    }
    cells.reverse();
    let points: Vec<(f32, f32)> = cells
        .iter()
        .skip(1)
        .map(|&(x, y)| (centre(x), centre(y)))
        .chain(std::iter::once(to))
        .collect();
    Some(shortcut(from, &points, clearance_m, discs))
}

/// Keeps only the waypoints line of sight needs.
fn shortcut(
    from: (f32, f32),
    points: &[(f32, f32)],
    clearance_m: f32,
    discs: &[Disc],
) -> Vec<(f32, f32)> {
    let mut out = Vec::new();
    let mut at = from;
    let mut i = 0;
    while i < points.len() {
        let mut far = i;
        for j in (i..points.len()).rev() {
            if segment_is_free_of(at, points[j], clearance_m, discs) {
                far = j;
                break;
            }
        }
        out.push(points[far]);
        at = points[far];
        i = far + 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use hal::field::{input_storage_pose, machine_approach_pose, MachineId};

    const R: f32 = 0.185;

    #[test]
    fn straight_line_when_free() {
        assert_eq!(plan((0.5, 0.5), (1.0, 0.5), R), Some(vec![(1.0, 0.5)]));
    }

    #[test]
    fn every_machine_is_reachable_from_the_storage_without_touching_anything() {
        let s = input_storage_pose();
        for m in MachineId::all() {
            let goal = machine_approach_pose(m);
            let path = plan((s.x_m, s.y_m), (goal.x_m, goal.y_m), R)
                .unwrap_or_else(|| panic!("no path to {m:?}"));
            assert_eq!(path.last(), Some(&(goal.x_m, goal.y_m)));
            let mut at = (s.x_m, s.y_m);
            for &p in &path {
                // Clearance minus a hair for the goal cell that touches its own machine.
                assert!(segment_is_free(at, p, R - 0.01), "{m:?} {at:?} -> {p:?}");
                at = p;
            }
        }
    }

    #[test]
    fn a_robot_in_the_way_is_driven_around() {
        // The lane below the first machine row, a robot standing in it.
        let (from, to) = ((0.6, 0.8), (4.6, 0.8));
        let robot = (2.6, 0.8, R);
        assert_eq!(plan(from, to, R), Some(vec![to]));
        let path = plan_around(from, to, R, &[robot]).unwrap_or_else(|| panic!("no way round"));
        assert_eq!(path.last(), Some(&to));
        let mut at = from;
        for &p in &path {
            assert!(
                segment_is_free_of(at, p, R - 0.01, &[robot]),
                "{at:?} -> {p:?}"
            );
            at = p;
        }
        assert!(path.len() > 1);
    }

    #[test]
    fn blocked_goal_surrounded_is_unreachable() {
        // Inside M5 with a clearance no lane allows.
        assert_eq!(plan((0.5, 0.5), (2.8, 2.8), 1.0), None);
    }
}
