//! The behaviour layer: reactive skills as small state machines, stepped once per cycle with
//! what the robot perceives, each returning the twist it wants and its outcome (RUNNING,
//! FINAL, FAILED). Pure: no I/O, no clock; the safety layer clamps and may veto the twist.

use super::planner;
use super::traffic::{self, Teammates};
#[cfg(test)]
use hal::field::input_storage_pose;
use hal::field::{
    gate_pose, input_storage_pose_for, machine_approach_pose, recycling_pose, MachineId,
};
use hal::ir::IrScan;
use hal::skill::{FailReason, Perception, SkillOutcome, SkillRequest};
use hal::{wrap_angle, LightSignal, Pose2, Twist};

/// What the skills see each cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Perceived {
    pub pose: Pose2,
    pub ir: IrScan,
    pub has_puck: bool,
    pub light: Option<(MachineId, LightSignal)>,
    /// Where the teammates are (from their announcements over the team link).
    pub teammates: Teammates,
    /// World heading of the motion the bumper last stopped, while the robot still stands
    /// there ([`super::bump::BumpMemory`]): the next drive backs away from it first.
    pub bumped_towards: Option<f32>,
}

/// Controller gains and tolerances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveTuning {
    pub max_linear_m_s: f32,
    pub max_angular_rad_s: f32,
    /// The drive's acceleration limit: how fast it can brake before a corner.
    pub max_linear_acc_m_s2: f32,
    pub robot_radius_m: f32,
    /// Proportional gains: speed per metre and per radian of error.
    pub gain_linear: f32,
    pub gain_angular: f32,
    pub goal_tolerance_m: f32,
    pub heading_tolerance_rad: f32,
    /// Obstacles nearer than this in the direction of motion slow the robot down.
    pub slow_down_within_m: f32,
    /// Fraction of the speed kept when an obstacle is at the IR's minimum range.
    pub min_speed_factor: f32,
    /// Cycles a drive may make no progress before it FAILS.
    pub stuck_cycles: u32,
    /// Which robot of the team (1..=3): picks its own spot at the input storage.
    pub robot_number: u8,
}

impl Default for DriveTuning {
    fn default() -> Self {
        Self {
            max_linear_m_s: 0.5,
            max_angular_rad_s: 0.78,
            max_linear_acc_m_s2: 1.0,
            robot_radius_m: 0.185,
            gain_linear: 1.5,
            gain_angular: 2.0,
            goal_tolerance_m: 0.03,
            heading_tolerance_rad: 0.05,
            slow_down_within_m: 0.3,
            min_speed_factor: 0.25,
            stuck_cycles: 15 * 10,
            robot_number: 1,
        }
    }
}

/// Result of one drive step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DriveStep {
    Driving(Twist),
    Arrived,
    Failed(FailReason),
}

/// Drives along planned waypoints to a pose, turning towards the goal heading on the way.
#[derive(Debug, Clone)]
pub struct DriveTo {
    goal: Pose2,
    waypoints: Vec<(f32, f32)>,
    next: usize,
    best_distance_m: f32,
    cycles_without_progress: u32,
    /// Cycles stopped in a row by something ahead that is not the goal.
    blocked_cycles: u32,
    /// The teammate that held this drive back in the last step.
    held_by: Option<u8>,
}

impl DriveTo {
    /// Plans from `from`; `None` when the goal cannot be reached.
    pub fn plan(from: Pose2, goal: Pose2, tuning: &DriveTuning) -> Option<Self> {
        Self::plan_around(from, goal, &[], None, tuning)
    }

    /// Plans from `from` around what the IR ring sees close by that the field does not
    /// explain (another robot), backing away first from one it touches.
    pub fn plan_seeing(
        from: Pose2,
        goal: Pose2,
        ir: &IrScan,
        tuning: &DriveTuning,
    ) -> Option<Self> {
        Self::plan_among(from, goal, ir, &[None; traffic::MAX_TEAMMATES], tuning)
    }

    /// [`Self::plan_seeing`], also around the teammates close by (as they announced
    /// themselves).
    pub fn plan_among(
        from: Pose2,
        goal: Pose2,
        ir: &IrScan,
        teammates: &Teammates,
        tuning: &DriveTuning,
    ) -> Option<Self> {
        Self::plan_bumped(from, goal, ir, teammates, None, tuning)
    }

    /// [`Self::plan_among`] from what the robot perceives, backing away first from what
    /// its bumper last met if it still stands there.
    pub fn plan_for(p: &Perceived, goal: Pose2, tuning: &DriveTuning) -> Option<Self> {
        Self::plan_bumped(p.pose, goal, &p.ir, &p.teammates, p.bumped_towards, tuning)
    }

    fn plan_bumped(
        from: Pose2,
        goal: Pose2,
        ir: &IrScan,
        teammates: &Teammates,
        bumped_towards: Option<f32>,
        tuning: &DriveTuning,
    ) -> Option<Self> {
        let r = tuning.robot_radius_m;
        let mut discs = robots_seen(from, ir, r, SEEN_WITHIN_M, |_| true);
        discs.extend(teammate_discs(from, teammates, r, MATES_PLANNED_WITHIN_M));
        Self::plan_around(from, goal, &discs, bumped_towards, tuning)
            .or_else(|| Self::plan_around(from, goal, &[], bumped_towards, tuning))
    }

    fn plan_around(
        from: Pose2,
        goal: Pose2,
        discs: &[planner::Disc],
        bumped_towards: Option<f32>,
        tuning: &DriveTuning,
    ) -> Option<Self> {
        let r = tuning.robot_radius_m;
        // A robot touching an obstacle first moves clear of it: a plan from inside an
        // obstacle's margin would drive straight back into it.
        let escape = escape_point(from, r, discs, bumped_towards);
        let start = escape.unwrap_or((from.x_m, from.y_m));
        let to = (goal.x_m, goal.y_m);
        // Keep a margin to what the path passes (the controller cuts corners a little);
        // the lanes between machines are narrow, so fall back to the bare radius.
        let path = planner::plan_around(start, to, r + PATH_MARGIN_M, discs)
            .or_else(|| planner::plan_around(start, to, r, discs))?;
        let waypoints = escape.into_iter().chain(path).collect();
        Some(Self {
            goal,
            waypoints,
            next: 0,
            best_distance_m: f32::INFINITY,
            cycles_without_progress: 0,
            blocked_cycles: 0,
            held_by: None,
        })
    }

    /// A straight move without planning (short moves next to a machine).
    pub fn straight(goal: Pose2) -> Self {
        Self {
            goal,
            waypoints: vec![(goal.x_m, goal.y_m)],
            next: 0,
            best_distance_m: f32::INFINITY,
            cycles_without_progress: 0,
            blocked_cycles: 0,
            held_by: None,
        }
    }

    /// The teammate that held this drive back in its last step, if one did.
    pub fn held_by(&self) -> Option<u8> {
        self.held_by
    }

    pub fn step(&mut self, p: &Perceived, t: &DriveTuning) -> DriveStep {
        let pose = p.pose;
        let last = self.waypoints.len().saturating_sub(1);
        let mut target = self
            .waypoints
            .get(self.next)
            .copied()
            .unwrap_or((self.goal.x_m, self.goal.y_m));
        let mut dist = ((target.0 - pose.x_m).powi(2) + (target.1 - pose.y_m).powi(2)).sqrt();
        // Intermediate waypoints are passed loosely, but only where the straight line on
        // to the next one clears every obstacle by the robot's radius: cutting the corner
        // of a machine there is what pressed the bumper. The final one exactly.
        while self.next < last
            && (dist < WAYPOINT_REACHED_M
                || (dist < WAYPOINT_PASS_M
                    && planner::segment_is_free(
                        (pose.x_m, pose.y_m),
                        self.waypoints[self.next + 1],
                        t.robot_radius_m + CORNER_CLEARANCE_M,
                    )))
        {
            self.next += 1;
            target = self.waypoints[self.next];
            dist = ((target.0 - pose.x_m).powi(2) + (target.1 - pose.y_m).powi(2)).sqrt();
        }
        let heading_error = wrap_angle(self.goal.phi_rad - pose.phi_rad);
        if self.next == last
            && dist <= t.goal_tolerance_m
            && heading_error.abs() <= t.heading_tolerance_rad
        {
            return DriveStep::Arrived;
        }

        // Progress watchdog on the remaining distance along the plan.
        let remaining = dist + self.remaining_after(self.next);
        // Progress is a real step along the plan: creeping a centimetre at a time counted
        // as progress (5 mm), and a robot sliding around a dead teammate's body that
        // stood on its goal crept on for 64 s to 85 s before the drive failed (kill-one
        // seeds 59 and 91: every stall of the 100 games).
        if remaining < self.best_distance_m - MIN_PROGRESS_M {
            self.best_distance_m = remaining;
            self.cycles_without_progress = 0;
        } else if heading_error.abs() <= t.heading_tolerance_rad {
            self.cycles_without_progress += 1;
            if self.cycles_without_progress > t.stuck_cycles {
                return DriveStep::Failed(FailReason::DriveFailed);
            }
        }

        // Brake in time: the drive decelerates at most at its limit, and a robot still
        // fast at a sharp turn swings wide into the machine the lane passes (the lanes
        // leave 7 cm a side). So: slow to a turning speed by the point where the next leg
        // begins, and to a stop at the goal.
        let brake = BRAKE_SHARE * t.max_linear_acc_m_s2;
        let corner_speed = if self.next < last {
            let turn = turn_angle((pose.x_m, pose.y_m), target, self.waypoints[self.next + 1]);
            let v_turn = if turn < SHALLOW_TURN_RAD {
                t.max_linear_m_s
            } else {
                TURN_SPEED_M_S
            };
            v_turn + (2.0 * brake * (dist - WAYPOINT_PASS_M).max(0.0)).sqrt()
        } else {
            0.02 + (2.0 * brake * dist).sqrt()
        };
        let speed = (t.gain_linear * (dist + self.remaining_after(self.next)))
            .min(t.max_linear_m_s)
            .min(t.gain_linear * 4.0 * dist.max(0.0) + 0.02)
            .min(corner_speed);
        let (lx, ly) = pose.to_local(target.0, target.1);
        let (mut vx, mut vy) = if dist > 1e-4 {
            (lx / dist * speed, ly / dist * speed)
        } else {
            (0.0, 0.0)
        };
        // Slow down for obstacles ahead in the direction of motion.
        let mut ir_blocked = false;
        let mut ahead_discs = Vec::new();
        if speed > 0.0 {
            let motion = vy.atan2(vx);
            if let Some(d) = p.ir.nearest_towards(motion, 25f32.to_radians()) {
                // Something right ahead that is not the station we drive to (another robot):
                // wait for it to move; the progress watchdog ends the wait.
                ir_blocked = d <= STOP_WITHIN_M && remaining > d + 0.15;
                if ir_blocked {
                    let ahead = |a: f32| wrap_angle(a - motion).abs() <= 25f32.to_radians();
                    ahead_discs = robots_seen(pose, &p.ir, t.robot_radius_m, STOP_WITHIN_M, ahead);
                }
                let f = if ir_blocked {
                    0.0
                } else {
                    ((d - hal::ir::IR_MIN_RANGE_M)
                        / (t.slow_down_within_m - hal::ir::IR_MIN_RANGE_M))
                        .clamp(t.min_speed_factor, 1.0)
                };
                vx *= f;
                vy *= f;
            }
        }
        // Keep the distance to the teammates (as they announced themselves): a teammate
        // in the way holds this robot back unless it stands at this drive's goal (a queue
        // at a gate: wait for it to leave).
        // Besides the announcements, the bodies the IR ring sees now: on a link that loses
        // and delays messages (10 %, up to 2 s) the newest announcement may be a second or
        // two old, and robots touched where the guard put a teammate from old news (the
        // 100 lossy games: 55 contacts). The IR's robot stands still as far as this robot
        // knows; it brakes for the body it sees in any direction, not only ahead.
        let mut near: Vec<traffic::Teammate> = p.teammates.iter().flatten().copied().collect();
        near.extend(
            robots_seen(
                pose,
                &p.ir,
                t.robot_radius_m,
                hal::ir::IR_MAX_RANGE_M,
                |_| true,
            )
            .into_iter()
            .map(|(x_m, y_m, _)| traffic::Teammate {
                number: 0,
                x_m,
                y_m,
                vx_m_s: 0.0,
                vy_m_s: 0.0,
                silent: false,
            }),
        );
        let wanted = vx.hypot(vy);
        let guarded = traffic::keep_distance_from(
            &pose,
            Twist::new(vx, vy, 0.0),
            &near,
            t.robot_radius_m,
            t.max_linear_acc_m_s2,
        );
        // The guard cuts the part of the motion that closes in on the teammate; what is
        // left runs past it, and in a lane between machines that is into a machine (team
        // seed 32: robot 1, meeting robot 2 in the M9/M10 lane, pressed against M9 twice,
        // gave M10 up and stood still 61 s with its S2). A way past that brings the body
        // nearer a machine or wall than the corner clearance is no way: the robot stands,
        // held back (and plans around the teammate after its patience).
        let guarded = if wanted > 1e-3 && !slide_keeps_clear(&pose, (vx, vy), guarded, t) {
            Twist::new(0.0, 0.0, guarded.omega_rad_s)
        } else {
            guarded
        };
        let held = wanted > 0.03 && guarded.linear_speed_m_s() < HELD_BACK_SHARE * wanted;
        // The nearest teammate is the one in the way.
        self.held_by = p.teammates[0].filter(|_| held).map(|m| m.number);
        let mate_blocked = held
            && p.teammates.iter().flatten().all(|m| {
                (m.x_m - self.goal.x_m).hypot(m.y_m - self.goal.y_m) > 2.0 * t.robot_radius_m
            });
        (vx, vy) = (guarded.vx_m_s, guarded.vy_m_s);
        let blocked = ir_blocked || mate_blocked;
        self.blocked_cycles = if blocked { self.blocked_cycles + 1 } else { 0 };
        // Blocked a while: plan around it. Robots give way by number (the highest
        // replans first), so two that meet head-on do not both turn the same way.
        let patience = REPLAN_AFTER_CYCLES * u32::from(4u8.saturating_sub(t.robot_number).max(1));
        if blocked && self.blocked_cycles >= patience {
            self.blocked_cycles = 0;
            ahead_discs.extend(teammate_discs(
                pose,
                &p.teammates,
                t.robot_radius_m,
                MATES_PLANNED_WITHIN_M,
            ));
            // Only for a robot: a machine in the way is the watchdog's business.
            if let Some(mut around) = (!ahead_discs.is_empty())
                .then(|| Self::plan_around(pose, self.goal, &ahead_discs, None, t))
                .flatten()
            {
                // The watchdog runs on: a drive that replans around a teammate again and
                // again without getting anywhere still fails.
                around.best_distance_m = around.distance_from(&pose);
                around.cycles_without_progress = self.cycles_without_progress;
                *self = around;
                return DriveStep::Driving(Twist::ZERO);
            }
        }
        let omega =
            (t.gain_angular * heading_error).clamp(-t.max_angular_rad_s, t.max_angular_rad_s);
        DriveStep::Driving(Twist::new(vx, vy, omega))
    }

    /// The length of the plan from `pose`, all of it ahead.
    fn distance_from(&self, pose: &Pose2) -> f32 {
        self.waypoints.first().map_or(0.0, |w| {
            (w.0 - pose.x_m).hypot(w.1 - pose.y_m) + self.remaining_after(0)
        })
    }

    fn remaining_after(&self, i: usize) -> f32 {
        self.waypoints
            .windows(2)
            .skip(i)
            .map(|w| ((w[1].0 - w[0].0).powi(2) + (w[1].1 - w[0].1).powi(2)).sqrt())
            .sum()
    }
}

/// A drive makes progress when its way left shrinks by this much; [`DriveTuning`]'s
/// `stuck_cycles` without it, it fails.
const MIN_PROGRESS_M: f32 = 0.2;

/// How far ahead (seconds of the motion) [`slide_keeps_clear`] looks.
const SLIDE_LOOK_S: f32 = 0.3;

/// Whether `guarded` (the teammate guard's cut of the body-frame motion `wanted`) keeps
/// the robot clear of machines and walls: a cut that changed the motion's direction may
/// not take the body, [`SLIDE_LOOK_S`] on, nearer than the corner clearance to them
/// unless it gains room. A cut that only slows the planned motion down keeps to the plan.
fn slide_keeps_clear(pose: &Pose2, wanted: (f32, f32), guarded: Twist, t: &DriveTuning) -> bool {
    let (gx, gy) = (guarded.vx_m_s, guarded.vy_m_s);
    let w = wanted.0.hypot(wanted.1);
    if w <= 1e-6 {
        return true;
    }
    // The part of the guarded motion across the wanted one.
    let across = (gx * wanted.1 - gy * wanted.0).abs() / w;
    if across < 0.01 {
        return true;
    }
    let (s, c) = pose.phi_rad.sin_cos();
    let (wx, wy) = (c * gx - s * gy, s * gx + c * gy);
    let room = |x: f32, y: f32| hal::field::clearance(x, y, None);
    let now = room(pose.x_m, pose.y_m);
    let then = room(pose.x_m + wx * SLIDE_LOOK_S, pose.y_m + wy * SLIDE_LOOK_S);
    then >= t.robot_radius_m + CORNER_CLEARANCE_M || then >= now
}

/// An intermediate waypoint this close is passed (heading for the next one) ...
const WAYPOINT_PASS_M: f32 = 0.1;
/// ... when the way on keeps this much beyond the radius; this close it is reached anyway.
const CORNER_CLEARANCE_M: f32 = 0.015;
const WAYPOINT_REACHED_M: f32 = 0.03;

/// Share of the drive's acceleration limit the controller plans to brake with.
const BRAKE_SHARE: f32 = 0.7;
/// Turns sharper than this are taken at [`TURN_SPEED_M_S`].
const SHALLOW_TURN_RAD: f32 = 0.35;
const TURN_SPEED_M_S: f32 = 0.12;

/// The angle between the leg a -> b and the leg b -> c.
fn turn_angle(a: (f32, f32), b: (f32, f32), c: (f32, f32)) -> f32 {
    let h1 = (b.1 - a.1).atan2(b.0 - a.0);
    let h2 = (c.1 - b.1).atan2(c.0 - b.0);
    wrap_angle(h2 - h1).abs()
}

/// Obstacles this close ahead stop the robot unless they are its goal.
const STOP_WITHIN_M: f32 = 0.07;

/// Extra clearance the planner keeps beyond the robot's radius where there is room.
const PATH_MARGIN_M: f32 = 0.03;
/// How far a robot in contact with an obstacle moves away before following its plan.
const ESCAPE_M: f32 = 0.12;
/// A robot this close to an obstacle (by its pose) counts as touching it.
const ESCAPE_WITHIN_M: f32 = 0.05;

/// Escape directions at least this far from the heading the bumper stopped lead back away
/// from what it met (7 of the 16, within 67.5 degrees of straight back).
const BACK_AWAY_FROM_RAD: f32 = 1.95;

/// The first step of a bumped robot's escape, which must not lose room.
const ESCAPE_FIRST_STEP_M: f32 = 0.02;

/// An escape point must leave at least this much more room than where the robot stands.
const ESCAPE_GAIN_M: f32 = 0.01;

/// For a robot closer to an obstacle (or a disc) than its radius (plus a little), the
/// nearest point [`ESCAPE_M`] away, trying 16 directions, that is clear of everything and
/// leaves more room than here. For one whose bumper stopped a motion heading
/// `bumped_towards` where it still stands, whatever its pose says: of the directions
/// leading back away from what it met, the one that leaves the most room.
fn escape_point(
    from: Pose2,
    radius_m: f32,
    discs: &[planner::Disc],
    bumped_towards: Option<f32>,
) -> Option<(f32, f32)> {
    // The margin covers the odometry's few centimetres of error: a robot whose pose says
    // 2 cm clear may be pressed against the machine, and planning along its edge pressed
    // the bumper again in the first cycle, skill after skill. A clear point is not enough
    // either: along a machine's edge towards its corner (clear by the pose, 3.5 cm off)
    // it pressed the corner again, every skill for the last 340 s of a game.
    let here = (from.x_m, from.y_m);
    let here_room = planner::clearance_of(here, discs);
    let points = (0..16)
        .map(|i| i as f32 * core::f32::consts::TAU / 16.0)
        .map(|a| {
            (
                a,
                (from.x_m + ESCAPE_M * a.cos(), from.y_m + ESCAPE_M * a.sin()),
            )
        });
    if let Some(bumped) = bumped_towards {
        let back_away = |a: f32| wrap_angle(a - bumped).abs() >= BACK_AWAY_FROM_RAD;
        // The first centimetres must not lose room either: pressed against a corner, a
        // move whose end has room but whose start grazes the corner is stopped at once
        // (a robot of seed 63 with a dead teammate went back and forth so, 1,983 bumps).
        // Each obstacle it touches counts alone: the least room of all may be a teammate's
        // disc, grown by the gap the guard keeps, while the body grazes a machine.
        let touch = radius_m + ESCAPE_WITHIN_M;
        let first_step_gains = |a: f32| {
            let step = (
                from.x_m + ESCAPE_FIRST_STEP_M * a.cos(),
                from.y_m + ESCAPE_FIRST_STEP_M * a.sin(),
            );
            let field = |p: (f32, f32)| hal::field::clearance(p.0, p.1, None);
            let field_ok = field(here) >= touch || field(step) >= field(here);
            field_ok
                && discs.iter().all(|d| {
                    let room = |p: (f32, f32)| (p.0 - d.0).hypot(p.1 - d.1) - d.2;
                    room(here) >= touch || room(step) >= room(here)
                })
        };
        let backing: Vec<(f32, (f32, f32))> = points.filter(|&(a, _)| back_away(a)).collect();
        let gaining: Vec<(f32, (f32, f32))> = backing
            .iter()
            .copied()
            .filter(|&(a, _)| first_step_gains(a))
            .collect();
        let choices = if gaining.is_empty() { backing } else { gaining };
        return choices
            .into_iter()
            .map(|(_, p)| (p, planner::clearance_of(p, discs)))
            // The first of equals wins: a stable choice.
            .fold(
                None,
                |best: Option<((f32, f32), f32)>, (p, room)| match best {
                    Some((_, r)) if r + 1e-4 >= room => best,
                    _ => Some((p, room)),
                },
            )
            .map(|(p, _)| p);
    }
    if planner::segment_is_free_of(here, here, radius_m + ESCAPE_WITHIN_M, discs) {
        return None;
    }
    points.map(|(_, p)| p).find(|&p| {
        planner::segment_is_free_of(p, p, radius_m + PATH_MARGIN_M, discs)
            && planner::clearance_of(p, discs) >= here_room + ESCAPE_GAIN_M
    })
}

/// A reading this close to a machine or wall (by the odometry's pose, a few centimetres
/// off) is that machine or wall.
const EXPLAINED_WITHIN_M: f32 = 0.1;
/// Another robot seen this close (IR, from the body's edge) is planned around when a
/// skill starts.
const SEEN_WITHIN_M: f32 = 0.2;
/// Cycles a drive waits for a robot ahead before the highest-numbered robot plans around
/// it (robot 2 waits twice, robot 1 three times as long).
const REPLAN_AFTER_CYCLES: u32 = 15;

/// A drive the teammate guard slows below this share of what it wants is held back.
const HELD_BACK_SHARE: f32 = 0.2;
/// Teammates whose body is this close to this robot's are planned around.
const MATES_PLANNED_WITHIN_M: f32 = 0.5;

/// The teammates whose bodies are within `within_m` of this robot's, and those silent
/// long (a dead robot's body, wherever it stands), as discs grown by the gap the guard
/// keeps. Planned around from the start, a dead body in a lane costs one detour; met on
/// the way, it held a robot back before each replan (kill-one seed 46: robot 2 took
/// 42 s for a 3 m drive past robot 3's body at its waiting place, a stall).
fn teammate_discs(
    pose: Pose2,
    teammates: &Teammates,
    radius_m: f32,
    within_m: f32,
) -> Vec<planner::Disc> {
    teammates
        .iter()
        .flatten()
        .filter(|m| m.silent || m.distance_to(&pose) - 2.0 * radius_m <= within_m)
        .map(|m| (m.x_m, m.y_m, radius_m + traffic::MIN_GAP_M))
        .collect()
}

/// What the IR ring sees within `within_m` in the directions `towards` (robot frame)
/// that is not a wall or machine: robots, each a disc of this robot's radius behind the
/// reading.
fn robots_seen(
    pose: Pose2,
    ir: &IrScan,
    radius_m: f32,
    within_m: f32,
    towards: impl Fn(f32) -> bool,
) -> Vec<planner::Disc> {
    ir.distances_m
        .iter()
        .enumerate()
        .filter(|&(i, &d)| {
            d > hal::ir::IR_NO_READING && d <= within_m && towards(hal::ir::sensor_angle_rad(i))
        })
        .filter_map(|(i, &d)| {
            let a = pose.phi_rad + hal::ir::sensor_angle_rad(i);
            let (c, s) = (a.cos(), a.sin());
            let edge = (pose.x_m + (radius_m + d) * c, pose.y_m + (radius_m + d) * s);
            // A reading the field explains is a machine or a wall.
            (!hal::field::is_blocked(edge.0, edge.1, EXPLAINED_WITHIN_M)).then(|| {
                let centre = radius_m + d + radius_m;
                (pose.x_m + centre * c, pose.y_m + centre * s, radius_m)
            })
        })
        .collect()
}

/// Where to back away to after working a station: the longest back-off (up to
/// [`BACK_OFF_M`]) that keeps the robot's radius clear of walls and machines, or `None`
/// when there is no room behind (between two machine rows the lane is narrow).
fn leave_pose(pose: Pose2, t: &DriveTuning) -> Option<Pose2> {
    // The odometry's error margin, as for escaping: backing towards a machine the pose
    // says is 2 cm away may press the bumper.
    let clearance = t.robot_radius_m + ESCAPE_WITHIN_M;
    [BACK_OFF_M, BACK_OFF_M / 2.0, BACK_OFF_M / 5.0]
        .into_iter()
        .map(|d| backed_off(pose, d))
        .find(|to| planner::segment_is_free((pose.x_m, pose.y_m), (to.x_m, to.y_m), clearance))
}

fn backed_off(pose: Pose2, distance_m: f32) -> Pose2 {
    Pose2::new(
        pose.x_m - distance_m * pose.phi_rad.cos(),
        pose.y_m - distance_m * pose.phi_rad.sin(),
        pose.phi_rad,
    )
}

/// Cycles to wait at the storage for a puck, and at a gate for it to take the puck.
const WAIT_CYCLES: u32 = 30;
/// Cycles to let a machine's light react to a placed puck before reading it.
const LIGHT_SETTLE_CYCLES: u32 = 5;
/// Longest wait at a recycling unit for the raw puck (the unit takes 2 s).
const RECYCLE_WAIT_CYCLES: u32 = 15 * 6;
/// Longest wait at a machine: past the longest processing time (T3, 60 s).
const PROCESSING_WAIT_CYCLES: u32 = 15 * 65;
/// Within this distance of a station's pose, a puck leaving the robot was placed, not lost.
const NEAR_STATION_M: f32 = 0.15;
/// Distance to back away after working a station.
const BACK_OFF_M: f32 = 0.1;

#[derive(Debug, Clone)]
enum Phase {
    /// Letting go of a puck the agent does not want (counting cycles); then `then` starts,
    /// planned from wherever the robot is (`None`: the release was the whole skill).
    Release {
        waited: u32,
        then: Option<Pose2>,
    },
    Approach(DriveTo),
    /// Waiting at the station for the world to react, counting cycles.
    Wait(u32),
    Leave(DriveTo, Perception),
}

/// One running skill.
#[derive(Debug, Clone)]
pub struct Skill {
    request: SkillRequest,
    phase: Phase,
    /// The light seen when the puck was brought (BringPuckTo).
    light_before: Option<LightSignal>,
    /// The light differed from `light_before` at some point while waiting.
    light_changed: bool,
    /// Recycling: the unit took the junk (the gripper was empty at some point).
    puck_left: bool,
    /// Collecting: the cycle the machine's light turned green (its output is ready), from
    /// when the drive is asked to take it.
    ready_at: Option<u32>,
    /// Bringing a puck: the machine showed green before and after and took nothing, so an
    /// output lies under its light (the spot holds one puck; see `field_sim`).
    output_waits: bool,
}

impl Skill {
    /// Starts a skill; FAILED at once when the request makes no sense now. A robot asked to
    /// fetch a puck while it still holds one (the agent believes that puck lost after a
    /// failure) first releases it.
    pub fn start(
        request: SkillRequest,
        p: &Perceived,
        t: &DriveTuning,
    ) -> Result<Self, FailReason> {
        let goal = match request {
            SkillRequest::BringPuckTo(_)
            | SkillRequest::FeedTo(_)
            | SkillRequest::DeliverTo(_)
            | SkillRequest::Discard
            | SkillRequest::Recycle(_)
                if !p.has_puck =>
            {
                return Err(FailReason::InvalidRequest)
            }
            SkillRequest::Discard => None,
            SkillRequest::GetS0 => Some(input_storage_pose_for(t.robot_number)),
            SkillRequest::BringPuckTo(m)
            | SkillRequest::FeedTo(m)
            | SkillRequest::GetJunk(m)
            | SkillRequest::Collect(m) => Some(machine_approach_pose(m)),
            SkillRequest::DeliverTo(g) => Some(gate_pose(g)),
            SkillRequest::Recycle(u) => Some(recycling_pose(u)),
        };
        // A fetch with a puck in the gripper (one the agent believes lost) lets go first.
        let fetch = matches!(
            request,
            SkillRequest::GetS0 | SkillRequest::GetJunk(_) | SkillRequest::Collect(_)
        );
        let phase = match goal {
            Some(goal) if !(fetch && p.has_puck) => {
                Phase::Approach(DriveTo::plan_for(p, goal, t).ok_or(FailReason::DriveFailed)?)
            }
            then => Phase::Release { waited: 0, then },
        };
        Ok(Self {
            request,
            phase,
            light_before: None,
            light_changed: false,
            puck_left: false,
            ready_at: None,
            output_waits: false,
        })
    }

    /// The skill brought a puck to a machine that stayed green and took nothing: its
    /// output (another robot's, or one left by a robot that died) lies there.
    pub fn output_waits(&self) -> bool {
        self.output_waits
    }

    /// The teammate that holds the skill's drive back, if one does.
    pub fn held_by(&self) -> Option<u8> {
        match &self.phase {
            Phase::Approach(d) | Phase::Leave(d, _) => d.held_by(),
            _ => None,
        }
    }

    /// True while the skill asks the drive to let go of the puck.
    pub fn releasing(&self) -> bool {
        matches!(self.phase, Phase::Release { .. })
    }

    /// True while the skill asks the drive to take the puck lying in front of the robot
    /// (junk at the machine it stands at, or its output once the light is green).
    pub fn grabbing(&self) -> bool {
        let waiting = matches!(self.phase, Phase::Wait(_));
        match self.request {
            SkillRequest::GetJunk(_) => waiting,
            SkillRequest::Collect(_) => waiting && self.ready_at.is_some(),
            _ => false,
        }
    }

    /// What the skill perceived, once it is only leaving the station: the work is done.
    pub fn done_perception(&self) -> Option<Perception> {
        match self.phase {
            Phase::Leave(_, p) => Some(p),
            _ => None,
        }
    }

    pub fn request(&self) -> SkillRequest {
        self.request
    }

    /// One cycle: the twist the skill wants and its outcome.
    pub fn step(&mut self, p: &Perceived, t: &DriveTuning) -> (Twist, SkillOutcome) {
        match &mut self.phase {
            Phase::Release { waited, then } => {
                *waited += 1;
                if p.has_puck {
                    if *waited >= WAIT_CYCLES {
                        return (Twist::ZERO, SkillOutcome::Failed(FailReason::DriveFailed));
                    }
                    return (Twist::ZERO, SkillOutcome::Running);
                }
                self.phase = match then {
                    Some(goal) => match DriveTo::plan_for(p, *goal, t) {
                        Some(drive) => Phase::Approach(drive),
                        None => {
                            return (Twist::ZERO, SkillOutcome::Failed(FailReason::DriveFailed))
                        }
                    },
                    None => match leave_pose(p.pose, t) {
                        Some(goal) => Phase::Leave(DriveTo::straight(goal), Perception::Released),
                        None => return (Twist::ZERO, SkillOutcome::Final(Perception::Released)),
                    },
                };
                (Twist::ZERO, SkillOutcome::Running)
            }
            Phase::Approach(drive) => match drive.step(p, t) {
                DriveStep::Driving(tw) => {
                    if matches!(
                        self.request,
                        SkillRequest::BringPuckTo(_)
                            | SkillRequest::FeedTo(_)
                            | SkillRequest::DeliverTo(_)
                            | SkillRequest::Recycle(_)
                    ) && !p.has_puck
                    {
                        // Next to the station the puck leaving is the placement itself.
                        if p.pose.distance_to(&drive.goal) < NEAR_STATION_M {
                            self.phase = Phase::Wait(0);
                            return (Twist::ZERO, SkillOutcome::Running);
                        }
                        return (Twist::ZERO, SkillOutcome::Failed(FailReason::PuckLost));
                    }
                    if let (
                        SkillRequest::BringPuckTo(m) | SkillRequest::FeedTo(m),
                        Some((seen, l)),
                    ) = (self.request, p.light)
                    {
                        if seen == m {
                            self.light_before = Some(l);
                        }
                    }
                    (tw, SkillOutcome::Running)
                }
                DriveStep::Failed(r) => (Twist::ZERO, SkillOutcome::Failed(r)),
                DriveStep::Arrived => {
                    self.phase = Phase::Wait(0);
                    (Twist::ZERO, SkillOutcome::Running)
                }
            },
            Phase::Wait(cycles) => {
                *cycles += 1;
                let waited = *cycles;
                match self.react(p, waited) {
                    Ok(Some(perception)) => match leave_pose(p.pose, t) {
                        Some(goal) => {
                            self.phase = Phase::Leave(DriveTo::straight(goal), perception);
                            (Twist::ZERO, SkillOutcome::Running)
                        }
                        // No room behind: the work is done, stay where we are.
                        None => (Twist::ZERO, SkillOutcome::Final(perception)),
                    },
                    Ok(None) => (Twist::ZERO, SkillOutcome::Running),
                    Err(r) => (Twist::ZERO, SkillOutcome::Failed(r)),
                }
            }
            Phase::Leave(drive, perception) => match drive.step(p, t) {
                DriveStep::Driving(tw) => (tw, SkillOutcome::Running),
                // Leaving is best effort: what was perceived stands.
                DriveStep::Arrived | DriveStep::Failed(_) => {
                    (Twist::ZERO, SkillOutcome::Final(*perception))
                }
            },
        }
    }

    /// What the world did while the robot waits at the station: `Ok(None)` keeps waiting.
    fn react(&mut self, p: &Perceived, waited: u32) -> Result<Option<Perception>, FailReason> {
        let timed_out = waited >= WAIT_CYCLES;
        match self.request {
            SkillRequest::GetS0 => match (p.has_puck, timed_out) {
                (true, _) => Ok(Some(Perception::GotS0)),
                (false, true) => Err(FailReason::StorageEmpty),
                (false, false) => Ok(None),
            },
            SkillRequest::GetJunk(_) => match (p.has_puck, timed_out) {
                (true, _) => Ok(Some(Perception::GotJunk)),
                (false, true) => Err(FailReason::NoJunk),
                (false, false) => Ok(None),
            },
            // The unit takes the junk and hands a raw puck back after its recycling time.
            SkillRequest::Recycle(_) => {
                self.puck_left |= !p.has_puck;
                match (p.has_puck, self.puck_left) {
                    (true, true) => Ok(Some(Perception::Recycled)),
                    // The unit did not take the puck: still held (the agent keeps it).
                    (true, false) if timed_out => Err(FailReason::DriveFailed),
                    (false, _) if waited >= RECYCLE_WAIT_CYCLES => Err(FailReason::PuckLost),
                    _ => Ok(None),
                }
            }
            // Discard never waits at a station (it releases in place).
            SkillRequest::Discard => Ok(Some(Perception::Released)),
            SkillRequest::DeliverTo(_) => match (p.has_puck, timed_out) {
                (false, _) => Ok(Some(Perception::Delivered)),
                (true, true) => Err(FailReason::DriveFailed),
                (true, false) => Ok(None),
            },
            // The output is taken once the light is green; a light that never turns green,
            // or a grab that finds nothing, means no output lies there.
            SkillRequest::Collect(m) => {
                let green = p.light == Some((m, LightSignal::Green));
                if p.has_puck {
                    return Ok(Some(Perception::GotOutput));
                }
                match self.ready_at {
                    None if green => {
                        self.ready_at = Some(waited);
                        Ok(None)
                    }
                    None if waited >= PROCESSING_WAIT_CYCLES => Err(FailReason::NoOutput),
                    Some(at) if waited >= at + WAIT_CYCLES => Err(FailReason::NoOutput),
                    _ => Ok(None),
                }
            }
            SkillRequest::BringPuckTo(m) | SkillRequest::FeedTo(m) => {
                let feeding = matches!(self.request, SkillRequest::FeedTo(_));
                let now = p.light.filter(|(seen, _)| *seen == m).map(|(_, l)| l);
                if now.is_some() && now != self.light_before {
                    self.light_changed = true;
                }
                if waited < LIGHT_SETTLE_CYCLES {
                    return Ok(None);
                }
                let changed = self.light_changed;
                match (now, p.has_puck) {
                    // Input consumed, more needed: the puck stays in the machine.
                    (Some(LightSignal::Yellow), false) => {
                        Ok(Some(Perception::LightSeen(LightSignal::Yellow)))
                    }
                    // Yellow while the robot still has the puck: processing. Feeding, the
                    // robot leaves the puck to the machine; otherwise it waits.
                    (Some(LightSignal::Yellow), true) if feeding => {
                        Ok(Some(Perception::LeftProcessing))
                    }
                    (Some(LightSignal::Yellow), true) if waited < PROCESSING_WAIT_CYCLES => {
                        Ok(None)
                    }
                    // Green after a change: the cycle completed, the output is in hand.
                    (Some(LightSignal::Green), _) if changed => {
                        Ok(Some(Perception::LightSeen(LightSignal::Green)))
                    }
                    (Some(l), _) if changed && l != LightSignal::Yellow => {
                        Ok(Some(Perception::LightSeen(l)))
                    }
                    // Flashing before and after, puck still held: a wrong input again (the
                    // light had no way to change).
                    (Some(LightSignal::YellowFlashing), true) if waited >= WAIT_CYCLES => {
                        Ok(Some(Perception::LightSeen(LightSignal::YellowFlashing)))
                    }
                    // Nothing happened at all: the machine did not react to the puck.
                    _ if !changed && waited >= WAIT_CYCLES => {
                        self.output_waits = now == Some(LightSignal::Green) && p.has_puck;
                        Ok(Some(Perception::LightUnchanged))
                    }
                    _ if waited >= PROCESSING_WAIT_CYCLES => Ok(Some(Perception::LightUnchanged)),
                    _ => Ok(None),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hal::field::GateId;

    fn perceived(pose: Pose2, has_puck: bool) -> Perceived {
        Perceived {
            pose,
            ir: IrScan::EMPTY,
            has_puck,
            light: None,
            teammates: [None; traffic::MAX_TEAMMATES],
            bumped_towards: None,
        }
    }

    /// Moves a pose by a body twist for one 1/15 s cycle, exactly (no noise).
    fn integrate(pose: Pose2, tw: Twist) -> Pose2 {
        pose.advanced(tw, tw.omega_rad_s / 15.0, 1.0 / 15.0)
    }

    /// Distance from a point to the nearest machine's square (as the sim's bumper sees it).
    fn machine_clearance(x: f32, y: f32) -> f32 {
        let half = hal::field::MACHINE_SIZE_M / 2.0;
        hal::field::MACHINE_POSITIONS
            .iter()
            .map(|&(mx, my)| {
                let dx = ((x - mx).abs() - half).max(0.0);
                let dy = ((y - my).abs() - half).max(0.0);
                (dx * dx + dy * dy).sqrt()
            })
            .fold(f32::INFINITY, f32::min)
    }

    /// Drives from `from` to `to` through the drive's acceleration limits (as the safety
    /// layer passes the twist on); returns whether it arrived and the least clearance
    /// between the robot's edge and a machine on the way.
    fn drive_with_limits(from: Pose2, to: Pose2) -> (bool, f32) {
        let t = DriveTuning::default();
        let limits = hal::limits::MotionLimits::ROBOTINO2;
        let Some(mut drive) = DriveTo::plan(from, to, &t) else {
            return (false, f32::NEG_INFINITY);
        };
        let (mut pose, mut previous) = (from, Twist::ZERO);
        let mut least = f32::INFINITY;
        for _ in 0..15 * 90 {
            match drive.step(&perceived(pose, false), &t) {
                DriveStep::Driving(tw) => {
                    let tw = limits.clamp(previous, tw, 1.0 / 15.0);
                    previous = tw;
                    pose = integrate(pose, tw);
                    least = least.min(machine_clearance(pose.x_m, pose.y_m) - t.robot_radius_m);
                }
                DriveStep::Arrived => return (true, least),
                DriveStep::Failed(_) => return (false, least),
            }
        }
        (false, least)
    }

    /// Every way the agent drives (storage to each machine, machine to machine, machine to
    /// each gate) keeps off the machines, braking for the lanes' corners.
    #[test]
    fn no_drive_between_stations_touches_a_machine() {
        let machines: Vec<Pose2> = MachineId::all().map(machine_approach_pose).collect();
        let gates: Vec<Pose2> = (1..=3)
            .filter_map(GateId::new)
            .map(hal::field::gate_pose)
            .collect();
        let mut trips: Vec<(Pose2, Pose2)> = Vec::new();
        for robot in 1..=3 {
            let storage = input_storage_pose_for(robot);
            for &m in &machines {
                trips.push((storage, m));
                trips.push((m, storage));
            }
        }
        let recyclers: Vec<Pose2> = (1..=2)
            .filter_map(hal::field::RecyclingId::new)
            .map(recycling_pose)
            .collect();
        for &a in &machines {
            for &b in machines.iter().chain(gates.iter()).chain(recyclers.iter()) {
                if a != b {
                    trips.push((a, b));
                }
            }
            for &r in &recyclers {
                trips.push((r, a));
            }
        }
        let mut worst = (f32::INFINITY, Pose2::default(), Pose2::default());
        let mut touching = 0;
        let n = trips.len();
        for (a, b) in trips {
            // Leaving a station starts backed off from it, as the skills do.
            let from = leave_pose(a, &DriveTuning::default()).unwrap_or(a);
            let (arrived, least) = drive_with_limits(from, b);
            assert!(arrived, "{from:?} -> {b:?} did not arrive");
            touching += usize::from(least <= 0.0);
            if least < worst.0 {
                worst = (least, from, b);
            }
        }
        assert!(
            worst.0 > 0.0,
            "{touching} of {n} touched a machine, worst: {worst:?}"
        );
    }

    #[test]
    fn drive_to_reaches_the_goal_around_machines() {
        let t = DriveTuning::default();
        let start = input_storage_pose();
        let goal = machine_approach_pose(MachineId::new(5).unwrap_or_else(|| panic!()));
        let mut drive = DriveTo::plan(start, goal, &t).unwrap_or_else(|| panic!("plan"));
        let mut pose = start;
        let mut arrived = false;
        for _ in 0..15 * 60 {
            match drive.step(&perceived(pose, false), &t) {
                DriveStep::Driving(tw) => {
                    let tw = hal::limits::MotionLimits::ROBOTINO2.clamp_speed(tw);
                    pose = integrate(pose, tw);
                    assert!(
                        !hal::field::is_blocked(pose.x_m, pose.y_m, 0.15),
                        "{pose:?}"
                    );
                }
                DriveStep::Arrived => {
                    arrived = true;
                    break;
                }
                DriveStep::Failed(r) => panic!("{r:?}"),
            }
        }
        assert!(arrived, "{pose:?}");
        assert!(pose.distance_to(&goal) <= t.goal_tolerance_m);
    }

    #[test]
    fn obstacle_ahead_slows_the_robot() {
        let t = DriveTuning::default();
        let start = Pose2::new(1.0, 0.6, 0.0);
        let goal = Pose2::new(2.0, 0.6, 0.0);
        let mut free = DriveTo::plan(start, goal, &t).unwrap_or_else(|| panic!());
        let mut blocked = free.clone();
        let open = perceived(start, false);
        let mut near = open;
        near.ir.distances_m[0] = 0.1;
        let (DriveStep::Driving(a), DriveStep::Driving(b)) =
            (free.step(&open, &t), blocked.step(&near, &t))
        else {
            panic!("both should drive");
        };
        assert!(b.vx_m_s < a.vx_m_s * 0.5 && b.vx_m_s > 0.0, "{a:?} {b:?}");
        // A robot seen at the side does not slow the forward motion much; the guard only
        // takes the part that closes in on it (sensor 2 looks 80 degrees to the left).
        let mut side = open;
        side.ir.distances_m[2] = 0.05;
        let mut d = DriveTo::plan(start, goal, &t).unwrap_or_else(|| panic!());
        let DriveStep::Driving(c) = d.step(&side, &t) else {
            panic!("should drive");
        };
        let towards = hal::ir::sensor_angle_rad(2);
        let closing = c.vx_m_s * towards.cos() + c.vy_m_s * towards.sin();
        assert!(c.vx_m_s > 0.9 * a.vx_m_s, "{a:?} {c:?}");
        assert!(closing <= 1e-3, "closes in on the robot at the side: {c:?}");
    }

    #[test]
    fn a_robot_touching_a_machine_first_moves_clear() {
        let t = DriveTuning::default();
        // Against M6's corner (square 3.62..4.22 x 2.5..3.1), as a robot ended up once.
        let stuck = Pose2::new(4.40, 2.47, 2.8);
        assert!(hal::field::is_blocked(
            stuck.x_m,
            stuck.y_m,
            t.robot_radius_m
        ));
        let goal = machine_approach_pose(MachineId::new(8).unwrap_or_else(|| panic!()));
        let d = DriveTo::plan(stuck, goal, &t).unwrap_or_else(|| panic!("plan"));
        let (x, y) = d.waypoints[0];
        assert!(
            !hal::field::is_blocked(x, y, t.robot_radius_m),
            "escape {x},{y}"
        );
        assert!((x - stuck.x_m).hypot(y - stuck.y_m) < 0.13);
    }

    /// Where one robot of seed 25 ended up for the rest of the game: its body against
    /// M2's top-left corner (square 3.62..4.22 x 1.38..1.98), its odometry 3.5 cm off.
    const PRESSED_TRULY: (f32, f32) = (3.580, 2.1615);

    /// The room the escape's first leg leaves where the robot truly is, moved as its plan
    /// says (the leg from the believed pose to the first waypoint).
    fn true_room_after_escape(believed: Pose2, drive: &DriveTo) -> (f32, f32) {
        let (x, y) = drive.waypoints[0];
        let (dx, dy) = (x - believed.x_m, y - believed.y_m);
        let t = DriveTuning::default();
        let before = machine_clearance(PRESSED_TRULY.0, PRESSED_TRULY.1) - t.robot_radius_m;
        let after =
            machine_clearance(PRESSED_TRULY.0 + dx, PRESSED_TRULY.1 + dy) - t.robot_radius_m;
        (before, after)
    }

    /// Touching by its pose, the robot first moves to a clear point with more room: away
    /// from the corner. The first clear direction of 16 (+x, along the machine's edge,
    /// which loses room) pressed the corner again in truth, every skill for 340 s.
    #[test]
    fn a_robot_touching_a_corner_escapes_away_from_it() {
        let t = DriveTuning::default();
        let believed = Pose2::new(3.585, 2.197, core::f32::consts::FRAC_PI_2);
        let goal = machine_approach_pose(MachineId::new(3).unwrap_or_else(|| panic!()));
        let d = DriveTo::plan(believed, goal, &t).unwrap_or_else(|| panic!("plan"));
        let (before, after) = true_room_after_escape(believed, &d);
        assert!(before.abs() < 0.002, "{before}");
        assert!(
            after > 0.03,
            "escape to {:?} leaves {after}",
            d.waypoints[0]
        );
    }

    /// Clear by its pose (the odometry 8 cm off), but the bumper stopped a motion
    /// towards +x: the drive backs away from that first.
    #[test]
    fn a_bumped_robot_backs_away_whatever_its_pose_says() {
        let t = DriveTuning::default();
        let believed = Pose2::new(3.585, 2.24, core::f32::consts::FRAC_PI_2);
        let goal = machine_approach_pose(MachineId::new(6).unwrap_or_else(|| panic!()));
        let mut p = perceived(believed, false);
        let unaware = DriveTo::plan_for(&p, goal, &t).unwrap_or_else(|| panic!("plan"));
        // Unaware, it heads along the edge: into the corner, in truth.
        assert!(
            unaware.waypoints[0].0 > believed.x_m,
            "{:?}",
            unaware.waypoints
        );
        p.bumped_towards = Some(0.0);
        let d = DriveTo::plan_for(&p, goal, &t).unwrap_or_else(|| panic!("plan"));
        let (x, _) = d.waypoints[0];
        assert!(x < believed.x_m - 0.04, "escape to {:?}", d.waypoints[0]);
        let (_, after) = true_room_after_escape(believed, &d);
        assert!(
            after > 0.03,
            "escape to {:?} leaves {after}",
            d.waypoints[0]
        );
    }

    /// A teammate standing in the way (as it announced itself): the drive stops short of
    /// it, then plans around it and arrives without touching it.
    #[test]
    fn a_drive_goes_around_a_teammate_standing_in_the_way() {
        let t = DriveTuning::default();
        let (start, goal) = (Pose2::new(1.0, 0.6, 0.0), Pose2::new(3.0, 0.6, 0.0));
        let mate = traffic::Teammate {
            number: 2,
            x_m: 2.0,
            y_m: 0.6,
            vx_m_s: 0.0,
            vy_m_s: 0.0,
            silent: false,
        };
        let mut p = perceived(start, false);
        p.teammates[0] = Some(mate);
        let limits = hal::limits::MotionLimits::ROBOTINO2;
        let mut drive = DriveTo::plan_among(start, goal, &p.ir, &p.teammates, &t)
            .unwrap_or_else(|| panic!("plan"));
        let (mut previous, mut least) = (Twist::ZERO, f32::INFINITY);
        let mut arrived = false;
        for _ in 0..15 * 60 {
            match drive.step(&p, &t) {
                DriveStep::Driving(tw) => {
                    let tw = limits.clamp(previous, tw, 1.0 / 15.0);
                    previous = tw;
                    p.pose = integrate(p.pose, tw);
                    least = least.min(mate.distance_to(&p.pose) - 2.0 * t.robot_radius_m);
                }
                DriveStep::Arrived => {
                    arrived = true;
                    break;
                }
                DriveStep::Failed(r) => panic!("{r:?} at {:?}", p.pose),
            }
        }
        assert!(arrived, "{:?}", p.pose);
        assert!(least > 0.02, "came within {least} of the teammate");
    }

    /// A dead teammate's body far ahead in the way is planned around from the start (a
    /// live one that far off is not: it will have moved by then).
    #[test]
    fn a_drive_plans_around_a_silent_teammate_from_its_start() {
        let t = DriveTuning::default();
        let (start, goal) = (Pose2::new(0.5, 0.6, 0.0), Pose2::new(3.5, 0.6, 0.0));
        let mut mate = traffic::Teammate {
            number: 3,
            x_m: 2.0,
            y_m: 0.6,
            vx_m_s: 0.0,
            vy_m_s: 0.0,
            silent: false,
        };
        let passes_mate = |drive: &DriveTo, mate: &traffic::Teammate| {
            let mut from = (start.x_m, start.y_m);
            drive.waypoints.iter().any(|&to| {
                let (dx, dy) = (to.0 - from.0, to.1 - from.1);
                let len2 = (dx * dx + dy * dy).max(1e-9);
                let u =
                    (((mate.x_m - from.0) * dx + (mate.y_m - from.1) * dy) / len2).clamp(0.0, 1.0);
                let d = (from.0 + u * dx - mate.x_m).hypot(from.1 + u * dy - mate.y_m);
                from = to;
                d < 2.0 * t.robot_radius_m
            })
        };
        let mut p = perceived(start, false);
        p.teammates[0] = Some(mate);
        let alive = DriveTo::plan_for(&p, goal, &t).unwrap_or_else(|| panic!("plan"));
        assert!(passes_mate(&alive, &mate), "{:?}", alive.waypoints);
        mate.silent = true;
        p.teammates[0] = Some(mate);
        let dead = DriveTo::plan_for(&p, goal, &t).unwrap_or_else(|| panic!("plan"));
        assert!(!passes_mate(&dead, &mate), "{:?}", dead.waypoints);
    }

    /// Drives from `start` to `goal` for at most `seconds` with `mate` standing still
    /// where it is (as it announced itself, or where a dead teammate's body stopped):
    /// the drive's end (None: still driving), the seconds it took, the least gap between
    /// the robot's edge and a machine.
    fn drive_past_still_mate(
        start: Pose2,
        goal: Pose2,
        mate: (f32, f32),
        seconds: u32,
    ) -> (Option<DriveStep>, f32, f32) {
        let t = DriveTuning::default();
        let mut p = perceived(start, true);
        p.teammates[0] = Some(traffic::Teammate {
            number: 2,
            x_m: mate.0,
            y_m: mate.1,
            vx_m_s: 0.0,
            vy_m_s: 0.0,
            silent: false,
        });
        let limits = hal::limits::MotionLimits::ROBOTINO2;
        let mut drive = DriveTo::plan_among(start, goal, &p.ir, &p.teammates, &t)
            .unwrap_or_else(|| panic!("plan"));
        let (mut previous, mut least) = (Twist::ZERO, f32::INFINITY);
        for cycle in 0..15 * seconds {
            match drive.step(&p, &t) {
                DriveStep::Driving(tw) => {
                    let tw = limits.clamp(previous, tw, 1.0 / 15.0);
                    previous = tw;
                    p.pose = integrate(p.pose, tw);
                    least = least.min(machine_clearance(p.pose.x_m, p.pose.y_m) - t.robot_radius_m);
                }
                end => return (Some(end), cycle as f32 / 15.0, least),
            }
        }
        (None, seconds as f32, least)
    }

    /// Team seed 32: robot 1 drives up the lane between M9 and M10 to M10's approach,
    /// robot 2 stands in the lane ahead, a little to the right. The guard cuts the motion
    /// towards robot 2; what is left runs left, into M9 (the bumper stopped robot 1 there
    /// twice). The robot must stand rather than slide onto the machine.
    #[test]
    fn a_robot_held_back_by_a_teammate_does_not_slide_onto_a_machine() {
        let m10 = machine_approach_pose(MachineId::new(10).unwrap_or_else(|| panic!("M10")));
        for mate_x in [4.46, 4.51, 4.55] {
            let (_, _, least) =
                drive_past_still_mate(Pose2::new(4.48, 3.0, -1.57), m10, (mate_x, 4.06), 20);
            assert!(
                least > 0.0,
                "mate at x {mate_x}: touched a machine ({least})"
            );
        }
    }

    /// Kill-one seeds 59 and 91: a dead teammate's body stands on the recycling unit's
    /// approach; the robot crept around it, a centimetre at a time, for 64 s to 85 s before
    /// its drive failed (a stall). Creeping is no progress: the drive fails in a few
    /// watchdog periods.
    #[test]
    fn a_drive_to_a_goal_a_still_teammate_stands_on_fails_soon() {
        let t = DriveTuning::default();
        let goal = recycling_pose(hal::field::RecyclingId::new(1).unwrap_or_else(|| panic!("R1")));
        let (end, took, _) =
            drive_past_still_mate(Pose2::new(0.70, 1.10, -2.36), goal, (0.65, 0.67), 90);
        assert_eq!(
            end,
            Some(DriveStep::Failed(FailReason::DriveFailed)),
            "after {took} s"
        );
        let limit = 3.0 * t.stuck_cycles as f32 / 15.0;
        assert!(took <= limit, "failed after {took} s, more than {limit} s");
    }

    #[test]
    fn stuck_drive_fails() {
        let t = DriveTuning {
            stuck_cycles: 10,
            ..DriveTuning::default()
        };
        let start = Pose2::new(1.0, 0.6, 0.0);
        let mut d = DriveTo::straight(Pose2::new(2.0, 0.6, 0.0));
        let mut last = DriveStep::Arrived;
        for _ in 0..20 {
            last = d.step(&perceived(start, false), &t);
        }
        assert_eq!(last, DriveStep::Failed(FailReason::DriveFailed));
    }

    /// Runs a skill against a tiny world: `world` may change the perception each cycle.
    fn run(
        request: SkillRequest,
        start: Perceived,
        mut world: impl FnMut(&mut Perceived),
    ) -> SkillOutcome {
        let t = DriveTuning::default();
        let mut p = start;
        let mut skill = match Skill::start(request, &p, &t) {
            Ok(s) => s,
            Err(r) => return SkillOutcome::Failed(r),
        };
        for _ in 0..15 * 90 {
            let (tw, outcome) = skill.step(&p, &t);
            if outcome.is_terminal() {
                return outcome;
            }
            p.pose = integrate(p.pose, hal::limits::MotionLimits::ROBOTINO2.clamp_speed(tw));
            world(&mut p);
        }
        SkillOutcome::Running
    }

    #[test]
    fn get_s0_final_when_the_storage_hands_a_puck() {
        let storage = input_storage_pose();
        let outcome = run(
            SkillRequest::GetS0,
            perceived(Pose2::new(1.0, 0.6, 0.0), false),
            |p| {
                if p.pose.distance_to(&storage) < 0.05 {
                    p.has_puck = true;
                }
            },
        );
        assert_eq!(outcome, SkillOutcome::Final(Perception::GotS0));
    }

    #[test]
    fn get_s0_fails_on_an_empty_storage_and_when_holding() {
        let start = perceived(Pose2::new(1.0, 0.6, 0.0), false);
        assert_eq!(
            run(SkillRequest::GetS0, start, |_| {}),
            SkillOutcome::Failed(FailReason::StorageEmpty)
        );
        // Holding a puck the drive never lets go of: the release times out.
        let holding = perceived(Pose2::new(1.0, 0.6, 0.0), true);
        assert_eq!(
            run(SkillRequest::GetS0, holding, |_| {}),
            SkillOutcome::Failed(FailReason::DriveFailed)
        );
    }

    #[test]
    fn get_s0_releases_an_unwanted_puck_first_and_discard_releases_in_place() {
        let t = DriveTuning::default();
        let mut p = perceived(Pose2::new(1.0, 0.6, 0.0), true);
        let mut skill =
            Skill::start(SkillRequest::GetS0, &p, &t).unwrap_or_else(|r| panic!("{r:?}"));
        assert!(skill.releasing());
        assert_eq!(skill.step(&p, &t), (Twist::ZERO, SkillOutcome::Running));
        p.has_puck = false;
        let _ = skill.step(&p, &t);
        assert!(
            !skill.releasing(),
            "drives to the storage once the puck is gone"
        );
        let (tw, outcome) = skill.step(&p, &t);
        assert_eq!(outcome, SkillOutcome::Running);
        assert_ne!(tw, Twist::ZERO);

        let mut p = perceived(Pose2::new(1.0, 0.6, 0.0), true);
        let mut discard =
            Skill::start(SkillRequest::Discard, &p, &t).unwrap_or_else(|r| panic!("{r:?}"));
        assert!(discard.releasing());
        let _ = discard.step(&p, &t);
        p.has_puck = false;
        let mut outcome = SkillOutcome::Running;
        for _ in 0..100 {
            let (tw, o) = discard.step(&p, &t);
            outcome = o;
            if o.is_terminal() {
                break;
            }
            p.pose = integrate(p.pose, tw);
        }
        assert_eq!(outcome, SkillOutcome::Final(Perception::Released));
        let empty = perceived(Pose2::new(1.0, 0.6, 0.0), false);
        assert_eq!(
            Skill::start(SkillRequest::Discard, &empty, &t).err(),
            Some(FailReason::InvalidRequest)
        );
    }

    #[test]
    fn bring_puck_reads_the_new_light() {
        let m = MachineId::new(4).unwrap_or_else(|| panic!());
        let target = machine_approach_pose(m);
        let mut start = perceived(input_storage_pose(), true);
        start.light = Some((m, LightSignal::Green));
        let outcome = run(SkillRequest::BringPuckTo(m), start, |p| {
            if p.has_puck && p.pose.distance_to(&target) < 0.05 {
                p.has_puck = false;
                p.light = Some((m, LightSignal::Yellow));
            }
        });
        assert_eq!(
            outcome,
            SkillOutcome::Final(Perception::LightSeen(LightSignal::Yellow))
        );
    }

    #[test]
    fn bring_puck_waits_through_processing_for_green() {
        let m = MachineId::new(5).unwrap_or_else(|| panic!());
        let target = machine_approach_pose(m);
        let mut start = perceived(input_storage_pose(), true);
        start.light = Some((m, LightSignal::Green));
        let mut processing = None;
        let outcome = run(SkillRequest::BringPuckTo(m), start, |p| {
            if processing.is_none() && p.pose.distance_to(&target) < 0.05 {
                processing = Some(0);
                p.light = Some((m, LightSignal::Yellow));
            }
            if let Some(c) = processing.as_mut() {
                *c += 1;
                if *c == 200 {
                    p.light = Some((m, LightSignal::Green));
                }
            }
        });
        assert_eq!(
            outcome,
            SkillOutcome::Final(Perception::LightSeen(LightSignal::Green))
        );
    }

    #[test]
    fn feed_leaves_the_puck_once_the_machine_works_on_it() {
        let m = MachineId::new(6).unwrap_or_else(|| panic!());
        let target = machine_approach_pose(m);
        let mut start = perceived(input_storage_pose(), true);
        start.light = Some((m, LightSignal::Yellow));
        let mut cycles_there = 0;
        let outcome = run(SkillRequest::FeedTo(m), start, |p| {
            // The last input: the light stays yellow while the machine works for 50 s.
            if p.pose.distance_to(&target) < 0.15 {
                cycles_there += 1;
            }
        });
        assert_eq!(outcome, SkillOutcome::Final(Perception::LeftProcessing));
        assert!(cycles_there < 15 * 5, "waited {cycles_there} cycles there");
        // A consumed input (not the last) is read as usual.
        let outcome = run(SkillRequest::FeedTo(m), start, |p| {
            if p.has_puck && p.pose.distance_to(&target) < 0.05 {
                p.has_puck = false;
            }
        });
        assert_eq!(
            outcome,
            SkillOutcome::Final(Perception::LightSeen(LightSignal::Yellow))
        );
    }

    #[test]
    fn collect_takes_the_output_only_once_the_light_is_green() {
        let t = DriveTuning::default();
        let m = MachineId::new(6).unwrap_or_else(|| panic!());
        let target = machine_approach_pose(m);
        let mut start = perceived(input_storage_pose(), false);
        start.light = Some((m, LightSignal::Yellow));
        let mut skill =
            Skill::start(SkillRequest::Collect(m), &start, &t).unwrap_or_else(|r| panic!("{r:?}"));
        let mut p = start;
        let (mut outcome, mut there) = (SkillOutcome::Running, 0);
        for _ in 0..15 * 90 {
            let (tw, o) = skill.step(&p, &t);
            outcome = o;
            if o.is_terminal() {
                break;
            }
            if p.pose.distance_to(&target) < 0.05 {
                there += 1;
                if there == 200 {
                    p.light = Some((m, LightSignal::Green));
                }
            }
            if skill.grabbing() {
                assert_eq!(p.light, Some((m, LightSignal::Green)), "grab before green");
                p.has_puck = true;
            }
            p.pose = integrate(p.pose, hal::limits::MotionLimits::ROBOTINO2.clamp_speed(tw));
        }
        assert_eq!(outcome, SkillOutcome::Final(Perception::GotOutput));
        // Green but nothing to take, or never green: no output.
        let mut green = start;
        green.light = Some((m, LightSignal::Green));
        assert_eq!(
            run(SkillRequest::Collect(m), green, |_| {}),
            SkillOutcome::Failed(FailReason::NoOutput)
        );
        assert_eq!(
            run(SkillRequest::Collect(m), start, |_| {}),
            SkillOutcome::Failed(FailReason::NoOutput)
        );
    }

    #[test]
    fn bring_puck_reports_no_change_when_nothing_happens() {
        let m = MachineId::new(5).unwrap_or_else(|| panic!());
        let mut start = perceived(input_storage_pose(), true);
        start.light = Some((m, LightSignal::Green));
        let outcome = run(SkillRequest::BringPuckTo(m), start, |_| {});
        assert_eq!(outcome, SkillOutcome::Final(Perception::LightUnchanged));
    }

    /// A machine whose output still lies under its light takes no puck (the field sim
    /// refuses it): the light stays green and the robot keeps its puck. The skill says an
    /// output waits there; a machine that stays green after the puck left, or that the
    /// robot reaches without a puck, says nothing of the kind.
    #[test]
    fn bring_puck_to_a_green_machine_that_takes_nothing_says_an_output_waits() {
        let t = DriveTuning::default();
        let m = MachineId::new(3).unwrap_or_else(|| panic!());
        let target = machine_approach_pose(m);
        let ends = |request: SkillRequest, drop_there: bool| {
            let mut p = perceived(input_storage_pose(), true);
            p.light = Some((m, LightSignal::Green));
            let mut skill = Skill::start(request, &p, &t).unwrap_or_else(|r| panic!("{r:?}"));
            for _ in 0..15 * 90 {
                let (tw, outcome) = skill.step(&p, &t);
                if outcome.is_terminal() {
                    return (outcome, skill.output_waits());
                }
                p.pose = integrate(p.pose, hal::limits::MotionLimits::ROBOTINO2.clamp_speed(tw));
                if drop_there && p.pose.distance_to(&target) < 0.05 {
                    p.has_puck = false;
                }
            }
            (SkillOutcome::Running, skill.output_waits())
        };
        let unchanged = SkillOutcome::Final(Perception::LightUnchanged);
        assert_eq!(ends(SkillRequest::BringPuckTo(m), false), (unchanged, true));
        assert_eq!(ends(SkillRequest::FeedTo(m), false), (unchanged, true));
        // The puck went in and the light did not change: no output is known to wait.
        let (outcome, waits) = ends(SkillRequest::BringPuckTo(m), true);
        assert!(!waits, "{outcome:?}");
    }

    #[test]
    fn bring_puck_fails_when_the_puck_is_lost_on_the_way() {
        let m = MachineId::new(9).unwrap_or_else(|| panic!());
        let mut cycles = 0;
        let outcome = run(
            SkillRequest::BringPuckTo(m),
            perceived(input_storage_pose(), true),
            |p| {
                cycles += 1;
                if cycles == 10 {
                    p.has_puck = false;
                }
            },
        );
        assert_eq!(outcome, SkillOutcome::Failed(FailReason::PuckLost));
    }

    #[test]
    fn get_junk_takes_what_lies_at_the_machine_or_fails() {
        let t = DriveTuning::default();
        let m = MachineId::new(6).unwrap_or_else(|| panic!());
        let target = machine_approach_pose(m);
        let start = perceived(input_storage_pose(), false);
        // The world hands the junk only to a skill that asks for it, at the machine.
        let mut skill =
            Skill::start(SkillRequest::GetJunk(m), &start, &t).unwrap_or_else(|r| panic!("{r:?}"));
        let mut p = start;
        let mut outcome = SkillOutcome::Running;
        for _ in 0..15 * 90 {
            let (tw, o) = skill.step(&p, &t);
            outcome = o;
            if o.is_terminal() {
                break;
            }
            if skill.grabbing() {
                assert!(p.pose.distance_to(&target) < 0.05, "{:?}", p.pose);
                p.has_puck = true;
            }
            p.pose = integrate(p.pose, hal::limits::MotionLimits::ROBOTINO2.clamp_speed(tw));
        }
        assert_eq!(outcome, SkillOutcome::Final(Perception::GotJunk));
        assert_eq!(
            run(SkillRequest::GetJunk(m), start, |_| {}),
            SkillOutcome::Failed(FailReason::NoJunk)
        );
    }

    #[test]
    fn recycle_hands_the_junk_over_and_waits_for_the_raw_puck() {
        let unit = hal::field::RecyclingId::new(2).unwrap_or_else(|| panic!());
        let station = recycling_pose(unit);
        let start = perceived(input_storage_pose(), true);
        let mut at_unit = 0;
        let outcome = run(SkillRequest::Recycle(unit), start, |p| {
            if p.pose.distance_to(&station) < 0.05 {
                at_unit += 1;
                // The unit takes the junk, and 2 s later hands an S0 back.
                p.has_puck = at_unit > 30;
            }
        });
        assert_eq!(outcome, SkillOutcome::Final(Perception::Recycled));
        // A unit that never takes the puck: failed, the puck still held.
        assert_eq!(
            run(SkillRequest::Recycle(unit), start, |_| {}),
            SkillOutcome::Failed(FailReason::DriveFailed)
        );
        let empty = perceived(input_storage_pose(), false);
        assert_eq!(
            run(SkillRequest::Recycle(unit), empty, |_| {}),
            SkillOutcome::Failed(FailReason::InvalidRequest)
        );
    }

    #[test]
    fn deliver_final_when_the_gate_takes_the_puck() {
        let g = GateId::new(1).unwrap_or_else(|| panic!());
        let gate = gate_pose(g);
        let outcome = run(
            SkillRequest::DeliverTo(g),
            perceived(Pose2::new(1.0, 0.6, 0.0), true),
            |p| {
                if p.pose.distance_to(&gate) < 0.05 {
                    p.has_puck = false;
                }
            },
        );
        assert_eq!(outcome, SkillOutcome::Final(Perception::Delivered));
    }
}
