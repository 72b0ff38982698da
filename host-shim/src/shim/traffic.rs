//! Traffic between the robots of a team: each robot announces its pose and velocity every
//! cycle over the team link (a `pose` message, never through the simulator), keeps the
//! newest announcement of each teammate, predicts where the teammate is now, and its
//! drives keep their distance ([`keep_distance`]): the part of a twist that closes in on a
//! teammate is cut to what the drive can still brake before the two touch. A robot that
//! is only in a teammate's way is planned around (see `behaviour::DriveTo`); one standing
//! idle where a teammate must go (a station's approach) is asked to make way: the held
//! robot names it in its announcement, and the idle one drives to its waiting place.

use crate::team::TeamMsg;
use hal::{Pose2, Twist};

/// The team message kind of a pose announcement (the rules never see these).
pub const POSE_KIND: &str = "pose";

/// Where a teammate is, predicted for the current cycle, and how it moves (world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Teammate {
    pub number: u8,
    pub x_m: f32,
    pub y_m: f32,
    pub vx_m_s: f32,
    pub vy_m_s: f32,
    /// Not heard of for over [`SILENT_CYCLES`]: dead, as far as this robot can tell (a
    /// live one on a lossy link is heard again within a second or so).
    pub silent: bool,
}

impl Teammate {
    pub fn is_still(&self) -> bool {
        self.vx_m_s.hypot(self.vy_m_s) < 0.02
    }

    /// Distance between the two robots' centres.
    pub fn distance_to(&self, pose: &Pose2) -> f32 {
        (self.x_m - pose.x_m).hypot(self.y_m - pose.y_m)
    }
}

/// At most this many teammates (LLSF teams field three robots).
pub const MAX_TEAMMATES: usize = 2;

/// The teammates a robot knows of this cycle.
pub type Teammates = [Option<Teammate>; MAX_TEAMMATES];

/// An announcement: the sender's pose and its commanded velocity in the world frame, the
/// cycle it was sent in (the team link's clock, the same for every robot), and the
/// teammate that holds the sender's drive back (0: none).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoseReport {
    pub from: u8,
    pub cycle: u64,
    pub x_m: f32,
    pub y_m: f32,
    pub vx_m_s: f32,
    pub vy_m_s: f32,
    pub held_by: u8,
}

impl PoseReport {
    /// The report of a robot at `pose` commanding the body twist `twist`.
    pub fn new(from: u8, cycle: u64, pose: Pose2, twist: Twist) -> Self {
        let (s, c) = pose.phi_rad.sin_cos();
        Self {
            from,
            cycle,
            x_m: pose.x_m,
            y_m: pose.y_m,
            vx_m_s: c * twist.vx_m_s - s * twist.vy_m_s,
            vy_m_s: s * twist.vx_m_s + c * twist.vy_m_s,
            held_by: 0,
        }
    }

    /// The same report naming the teammate that holds the drive back.
    pub fn held_by(self, teammate: Option<u8>) -> Self {
        Self {
            held_by: teammate.unwrap_or(0),
            ..self
        }
    }

    pub fn to_msg(&self) -> TeamMsg {
        TeamMsg {
            from: self.from,
            seq: i64::try_from(self.cycle).unwrap_or(i64::MAX),
            kind: POSE_KIND.to_string(),
            to: 0,
            resource: "body".to_string(),
            rseq: 0,
            lease: 0.0,
            data: [self.x_m, self.y_m, self.vx_m_s, self.vy_m_s]
                .iter()
                .map(|v| format!("{v:.3}"))
                .chain(core::iter::once(self.held_by.to_string()))
                .collect(),
        }
    }

    /// `None` for another kind of message or a malformed announcement.
    pub fn from_msg(m: &TeamMsg) -> Option<Self> {
        if m.kind != POSE_KIND || m.data.len() != 5 {
            return None;
        }
        let mut v = [0f32; 4];
        for (slot, text) in v.iter_mut().zip(&m.data[..4]) {
            *slot = text.parse().ok().filter(|x: &f32| x.is_finite())?;
        }
        Some(Self {
            from: m.from,
            cycle: u64::try_from(m.seq).ok()?,
            x_m: v[0],
            y_m: v[1],
            vx_m_s: v[2],
            vy_m_s: v[3],
            held_by: m.data[4].parse().ok()?,
        })
    }
}

/// An announcement older than this (cycles) says too little about where the teammate is
/// going: it is no longer extrapolated, nor does it ask for the way.
const MAX_AGE_CYCLES: u64 = 15;
/// A teammate silent for longer (its messages lost or delayed, or the robot dead where
/// it stopped) stays an obstacle where it was last heard of, standing still once its
/// wheels would have stopped, until it is heard again: a dead robot's body stays on the
/// field for the rest of the game (forgotten after 20 s, as before, the others ran into
/// it again and again), and a live one on a link losing 10 % of its messages is heard
/// again within a few cycles.
///
/// One not heard of for this many cycles (3 s) is taken for dead: drives plan
/// around its body from their start.
pub const SILENT_CYCLES: u64 = 45;
/// A silent teammate's velocity is extrapolated this many cycles: its wheels stop then
/// (the motors' dead-man rule).
const PREDICT_CYCLES: u64 = 3;

/// How many cycles of its last velocity a teammate silent for `age` (> MAX_AGE_CYCLES)
/// cycles is carried on: where its wheels stopped (PREDICT_CYCLES), reached from the
/// MAX_AGE_CYCLES prediction of the cycle before by going back one cycle of its travel
/// per cycle. Put there at once, a teammate at 0.5 m/s jumped 40 cm back in one cycle
/// when its silence passed a second (a dead robot's phantom drove on for that second,
/// then stood back on its body), which no robot can do.
fn silent_cycles_ahead(age: u64) -> u64 {
    let back = age.saturating_sub(MAX_AGE_CYCLES);
    MAX_AGE_CYCLES.saturating_sub(back).max(PREDICT_CYCLES)
}

/// The time in `from_s..=to_s` at which `r`'s sender, driving on at its announced
/// velocity, comes nearest to `me`.
fn nearest_along(r: &PoseReport, from_s: f32, to_s: f32, me: &Pose2) -> f32 {
    let speed2 = r.vx_m_s * r.vx_m_s + r.vy_m_s * r.vy_m_s;
    if speed2 < 1e-9 {
        return from_s;
    }
    let t = ((me.x_m - r.x_m) * r.vx_m_s + (me.y_m - r.y_m) * r.vy_m_s) / speed2;
    t.clamp(from_s, to_s.max(from_s))
}

/// The newest announcement of each teammate (a late or duplicated one never replaces a
/// newer one).
#[derive(Debug, Clone, Default)]
pub struct TeamBoard {
    reports: Vec<PoseReport>,
}

impl TeamBoard {
    pub fn hear(&mut self, r: PoseReport) {
        match self.reports.iter_mut().find(|o| o.from == r.from) {
            Some(o) if o.cycle >= r.cycle => {}
            Some(o) => *o = r,
            None => {
                self.reports.push(r);
                self.reports.sort_by_key(|o| o.from);
            }
        }
    }

    /// A teammate whose fresh announcement says robot `me` holds it back.
    pub fn asking_way(&self, me: u8, cycle: u64) -> Option<u8> {
        self.reports
            .iter()
            .filter(|r| cycle.saturating_sub(r.cycle) <= MAX_AGE_CYCLES)
            .find(|r| r.held_by == me)
            .map(|r| r.from)
    }

    /// The teammates as they are predicted to stand in `cycle` (`dt_s` a cycle), nearest
    /// first.
    pub fn teammates(&self, cycle: u64, dt_s: f32, me: &Pose2) -> Teammates {
        let mut known: Vec<Teammate> = self
            .reports
            .iter()
            .map(|r| {
                let age = cycle.saturating_sub(r.cycle);
                // Not heard of this cycle, a teammate either drove on as it said for as
                // long as the news took (on a link delaying messages up to 2 s the newest
                // is often 8 cycles old; carried on for 3 cycles only, a teammate at
                // 0.5 m/s was placed 17 cm behind where it was, and the two touched), or
                // it is dead and its wheels stopped PREDICT_CYCLES after its last
                // command (placed where it would have driven on, seed 11's dead robot 3
                // was run into 0.7 s after its death by robot 2 following it). It is
                // kept apart from as the point of that stretch of its path nearest to
                // this robot.
                let driving = if age > MAX_AGE_CYCLES {
                    silent_cycles_ahead(age)
                } else {
                    age
                };
                let stopped = age.min(PREDICT_CYCLES);
                let ahead = nearest_along(r, stopped as f32 * dt_s, driving as f32 * dt_s, me);
                let (vx_m_s, vy_m_s) = if age > MAX_AGE_CYCLES {
                    (0.0, 0.0)
                } else {
                    (r.vx_m_s, r.vy_m_s)
                };
                Teammate {
                    number: r.from,
                    x_m: r.x_m + r.vx_m_s * ahead,
                    y_m: r.y_m + r.vy_m_s * ahead,
                    vx_m_s,
                    vy_m_s,
                    silent: age > SILENT_CYCLES,
                }
            })
            .collect();
        known.sort_by(|a, b| a.distance_to(me).total_cmp(&b.distance_to(me)));
        let mut out = [None; MAX_TEAMMATES];
        for (slot, t) in out.iter_mut().zip(known) {
            *slot = Some(t);
        }
        out
    }
}

/// The gap between two robots' bodies this guard keeps at the least: the odometry of
/// each is a few centimetres off, and an announcement is a cycle old.
pub const MIN_GAP_M: f32 = 0.07;
/// The share of the drive's deceleration the guard plans with.
const BRAKE_SHARE: f32 = 0.5;

/// Cuts the part of `twist` (body frame of `pose`) that closes in on a teammate to the
/// speed from which this robot can still stop (at `max_acc_m_s2`) before the gap falls
/// to [`MIN_GAP_M`], sharing the remaining gap with a teammate that closes in too.
/// Moving away or past a teammate stays free.
pub fn keep_distance(
    pose: &Pose2,
    twist: Twist,
    teammates: &Teammates,
    radius_m: f32,
    max_acc_m_s2: f32,
) -> Twist {
    let known: Vec<Teammate> = teammates.iter().flatten().copied().collect();
    keep_distance_from(pose, twist, &known, radius_m, max_acc_m_s2)
}

/// [`keep_distance`] from any number of robots (announced teammates, and bodies the IR
/// ring sees, standing still as far as the robot knows).
pub fn keep_distance_from(
    pose: &Pose2,
    twist: Twist,
    teammates: &[Teammate],
    radius_m: f32,
    max_acc_m_s2: f32,
) -> Twist {
    // Each teammate bounds the speed towards it: (direction, most speed allowed).
    let mut bounds = vec![((0f32, 0f32), f32::INFINITY); teammates.len()];
    for (b, t) in bounds.iter_mut().zip(teammates.iter()) {
        let (lx, ly) = pose.to_local(t.x_m, t.y_m);
        let d = lx.hypot(ly);
        if d < 1e-3 {
            continue;
        }
        let (ux, uy) = (lx / d, ly / d);
        // The teammate's own closing speed (its velocity towards this robot).
        let (s, c) = pose.phi_rad.sin_cos();
        let (tvx, tvy) = (c * t.vx_m_s + s * t.vy_m_s, -s * t.vx_m_s + c * t.vy_m_s);
        let theirs = -(tvx * ux + tvy * uy);
        let gap = d - 2.0 * radius_m - MIN_GAP_M;
        // Both brake: each gets half of what is left, less what the teammate closes in
        // during the cycle its announcement is late.
        // A body the IR ring sees (number 0) may be a teammate whose news is late on a
        // lossy link, driving towards this robot as this one drives towards it: each
        // keeps to its half of the gap (lossy seed 74: robots 1 and 3 left their
        // stations in the same cycle, met head-on, each braking for a still body, and
        // touched).
        let share = if theirs > 0.01 || t.number == 0 {
            0.5
        } else {
            1.0
        };
        let room = (share * gap - theirs.max(0.0) / 15.0).max(0.0);
        *b = ((ux, uy), (2.0 * BRAKE_SHARE * max_acc_m_s2 * room).sqrt());
    }
    let (mut vx, mut vy) = (twist.vx_m_s, twist.vy_m_s);
    let excess =
        |vx: f32, vy: f32, ((ux, uy), allowed): ((f32, f32), f32)| vx * ux + vy * uy - allowed;
    // Cutting the speed towards one teammate may add speed towards another (a robot
    // between two): project in turn a few times, and stand still if that does not
    // satisfy both.
    for _ in 0..4 {
        for &b in &bounds {
            let over = excess(vx, vy, b);
            if over > 0.0 {
                vx -= over * b.0 .0;
                vy -= over * b.0 .1;
            }
        }
    }
    if bounds.iter().any(|&b| excess(vx, vy, b) > 1e-3) {
        (vx, vy) = (0.0, 0.0);
    }
    Twist::new(vx, vy, twist.omega_rad_s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mate(x: f32, y: f32, vx: f32, vy: f32) -> Teammates {
        [
            Some(Teammate {
                number: 2,
                x_m: x,
                y_m: y,
                vx_m_s: vx,
                vy_m_s: vy,
                silent: false,
            }),
            None,
        ]
    }

    #[test]
    fn pose_reports_round_trip_and_reject_other_messages() {
        let r = PoseReport::new(
            2,
            77,
            Pose2::new(1.0, 2.0, core::f32::consts::FRAC_PI_2),
            Twist::new(0.3, 0.0, 0.1),
        );
        // Facing +y, driving forward: +y in the world.
        assert!(
            (r.vy_m_s - 0.3).abs() < 1e-5 && r.vx_m_s.abs() < 1e-5,
            "{r:?}"
        );
        let back = PoseReport::from_msg(&r.to_msg()).unwrap_or_else(|| panic!("decodes"));
        assert_eq!(back.from, 2);
        assert_eq!(back.cycle, 77);
        assert_eq!(back.held_by, 0);
        let asking = PoseReport::from_msg(&r.held_by(Some(3)).to_msg());
        assert_eq!(asking.map(|a| a.held_by), Some(3));
        assert!((back.y_m - 2.0).abs() < 1e-3);
        let mut news = r.to_msg();
        news.kind = "news".to_string();
        assert_eq!(PoseReport::from_msg(&news), None);
        let mut broken = r.to_msg();
        broken.data[1] = "NaN".to_string();
        assert_eq!(PoseReport::from_msg(&broken), None);
    }

    /// On a link that delays messages, the newest announcement is several cycles old:
    /// the teammate drove on meanwhile, and is predicted there.
    #[test]
    fn a_late_announcement_is_carried_on_for_its_age() {
        let mut b = TeamBoard::default();
        b.hear(PoseReport {
            from: 3,
            cycle: 100,
            x_m: 2.35,
            y_m: 4.40,
            vx_m_s: 0.48,
            vy_m_s: 0.0,
            held_by: 0,
        });
        // A robot it drives towards.
        let me = Pose2::new(3.5, 4.40, 0.0);
        let dt = 1.0 / 15.0;
        for age in [1, 8, MAX_AGE_CYCLES] {
            let t = b.teammates(100 + age, dt, &me)[0].unwrap_or_else(|| panic!("known"));
            let expected = 2.35 + 0.48 * age as f32 * dt;
            assert!((t.x_m - expected).abs() < 1e-4, "age {age}: {t:?}");
            assert!((t.vx_m_s - 0.48).abs() < 1e-6, "{t:?}");
        }
    }

    /// A teammate that fell silent may be dead, its wheels stopped PREDICT_CYCLES after
    /// its last command: a robot behind it keeps apart from where it stopped, not from
    /// where it would have driven on (seed 11 of the kill-one sweep: robot 2 ran into
    /// the dead robot 3 0.7 s after its death). Beside its path, the nearest point of
    /// the stretch between the two.
    #[test]
    fn a_silent_teammate_is_kept_apart_from_where_it_may_have_stopped() {
        let mut b = TeamBoard::default();
        b.hear(PoseReport {
            from: 3,
            cycle: 100,
            x_m: 1.0,
            y_m: 5.0,
            vx_m_s: 0.0,
            vy_m_s: 0.5,
            held_by: 0,
        });
        let dt = 1.0 / 15.0;
        let stopped_y = 5.0 + 0.5 * PREDICT_CYCLES as f32 * dt;
        let behind = Pose2::new(1.0, 4.4, 1.57);
        for age in [PREDICT_CYCLES, 8, MAX_AGE_CYCLES, MAX_AGE_CYCLES + 1, 200] {
            let t = b.teammates(100 + age, dt, &behind)[0].unwrap_or_else(|| panic!("known"));
            assert!((t.y_m - stopped_y).abs() < 1e-5, "age {age}: {t:?}");
            assert_eq!(t.x_m, 1.0);
        }
        // Beside the stretch it may have driven (5.1 .. 5.5 in 12 cycles): level with it.
        let beside = Pose2::new(1.6, 5.3, 0.0);
        let t = b.teammates(112, dt, &beside)[0].unwrap_or_else(|| panic!("known"));
        assert!((t.y_m - 5.3).abs() < 1e-4, "{t:?}");
        // Heard this cycle's news (age 1): where it said, carried one cycle on.
        let t = b.teammates(101, dt, &behind)[0].unwrap_or_else(|| panic!("known"));
        assert!((t.y_m - (5.0 + 0.5 * dt)).abs() < 1e-5, "{t:?}");
    }

    /// A teammate heard of within the last 3 s is alive as far as a robot can tell; one
    /// silent for longer is taken for dead (its body planned around from a drive's start).
    #[test]
    fn a_teammate_silent_over_three_seconds_is_taken_for_dead() {
        let mut b = TeamBoard::default();
        b.hear(PoseReport {
            from: 3,
            cycle: 100,
            x_m: 1.0,
            y_m: 5.0,
            vx_m_s: 0.0,
            vy_m_s: 0.0,
            held_by: 0,
        });
        let me = Pose2::new(4.0, 1.0, 0.0);
        let dt = 1.0 / 15.0;
        let silent = |age: u64| b.teammates(100 + age, dt, &me)[0].map(|t| t.silent);
        assert_eq!(silent(1), Some(false));
        assert_eq!(silent(SILENT_CYCLES), Some(false));
        assert_eq!(silent(SILENT_CYCLES + 1), Some(true));
        assert_eq!(silent(900), Some(true));
    }

    #[test]
    fn a_silent_teammate_stays_a_still_obstacle_where_it_stopped() {
        let mut b = TeamBoard::default();
        b.hear(PoseReport {
            from: 2,
            cycle: 100,
            x_m: 2.0,
            y_m: 1.0,
            vx_m_s: 0.5,
            vy_m_s: 0.0,
            held_by: 0,
        });
        let me = Pose2::new(0.0, 0.0, 0.0);
        let dt = 1.0 / 15.0;
        let fresh = b.teammates(101, dt, &me)[0].unwrap_or_else(|| panic!("known"));
        assert!(fresh.x_m > 2.0 && fresh.vx_m_s > 0.0, "{fresh:?}");
        // Silent: once back from where a live one would be, it stands where its last
        // command took it in PREDICT_CYCLES cycles, however long the silence (a dead
        // body stays on the field).
        let stopped_x = 2.0 + 0.5 * PREDICT_CYCLES as f32 * dt;
        let back_at = 2 * MAX_AGE_CYCLES - PREDICT_CYCLES;
        for silent in [back_at, back_at + 1, 15 * 20 + 1, 15 * 600] {
            let t = b.teammates(100 + silent, dt, &me)[0].unwrap_or_else(|| panic!("kept"));
            assert_eq!((t.y_m, t.vx_m_s, t.vy_m_s), (1.0, 0.0, 0.0), "{t:?}");
            assert!((t.x_m - stopped_x).abs() < 1e-5, "{t:?}");
        }
        // Heard again: its new pose replaces the old one.
        b.hear(PoseReport {
            from: 2,
            cycle: 9100,
            x_m: 4.0,
            y_m: 4.0,
            vx_m_s: 0.0,
            vy_m_s: 0.0,
            held_by: 0,
        });
        let t = b.teammates(9101, dt, &me)[0].unwrap_or_else(|| panic!("known"));
        assert_eq!((t.x_m, t.y_m), (4.0, 4.0));
    }

    /// However long a teammate is silent, its predicted place moves no faster than it
    /// drove: past MAX_AGE_CYCLES it goes back to where its wheels stopped, a cycle's
    /// travel per cycle, and is still (no jump at the second of silence).
    #[test]
    fn a_silent_teammate_never_jumps() {
        let mut b = TeamBoard::default();
        let (vx, vy) = (0.4, -0.3);
        b.hear(PoseReport {
            from: 2,
            cycle: 100,
            x_m: 2.0,
            y_m: 1.0,
            vx_m_s: vx,
            vy_m_s: vy,
            held_by: 0,
        });
        // Far ahead on its path: the prediction is where it drove on, while that lasts.
        let me = Pose2::new(6.0, -2.0, 0.0);
        let dt = 1.0 / 15.0;
        let step = f32::hypot(vx, vy) * dt;
        let at = |age: u64| b.teammates(100 + age, dt, &me)[0].unwrap_or_else(|| panic!("known"));
        let mut moved_back = false;
        for age in 0..3 * MAX_AGE_CYCLES {
            let (a, n) = (at(age), at(age + 1));
            let d = (n.x_m - a.x_m).hypot(n.y_m - a.y_m);
            assert!(
                d <= step + 1e-4,
                "age {age} -> {}: {d} m ({a:?} {n:?})",
                age + 1
            );
            if age >= MAX_AGE_CYCLES {
                assert!(n.is_still(), "age {}: {n:?}", age + 1);
            }
            // Going back along its path: against its velocity.
            moved_back |= (n.x_m - a.x_m) * vx + (n.y_m - a.y_m) * vy < -1e-4;
        }
        assert!(
            moved_back,
            "the prediction never went back to where it stopped"
        );
        let end = at(3 * MAX_AGE_CYCLES);
        let stopped = PREDICT_CYCLES as f32 * dt;
        assert!((end.x_m - (2.0 + vx * stopped)).abs() < 1e-5, "{end:?}");
        assert!((end.y_m - (1.0 + vy * stopped)).abs() < 1e-5, "{end:?}");
    }

    #[test]
    fn the_board_keeps_the_newest_report_and_stops_asking_with_old_ones() {
        let mut b = TeamBoard::default();
        let at = |cycle, x| PoseReport {
            from: 3,
            cycle,
            x_m: x,
            y_m: 1.0,
            vx_m_s: 0.0,
            vy_m_s: 0.0,
            held_by: 1,
        };
        b.hear(at(10, 1.0));
        b.hear(at(8, 2.0));
        let me = Pose2::new(0.0, 0.0, 0.0);
        let t = b.teammates(11, 1.0 / 15.0, &me)[0].unwrap_or_else(|| panic!("known"));
        assert_eq!(t.x_m, 1.0);
        assert_eq!(b.asking_way(1, 11), Some(3));
        assert_eq!(b.asking_way(2, 11), None);
        assert_eq!(b.asking_way(1, 10 + MAX_AGE_CYCLES + 1), None);
    }

    #[test]
    fn the_guard_stops_closing_in_but_lets_the_robot_pass_and_leave() {
        let me = Pose2::new(1.0, 1.0, 0.0);
        let r = 0.185;
        // A teammate touching distance plus the gap ahead: no speed towards it.
        let near = mate(1.0 + 2.0 * r + MIN_GAP_M, 1.0, 0.0, 0.0);
        let t = keep_distance(&me, Twist::new(0.5, 0.2, 0.3), &near, r, 1.0);
        assert!(t.vx_m_s.abs() < 1e-3, "{t:?}");
        assert!((t.vy_m_s - 0.2).abs() < 1e-5 && (t.omega_rad_s - 0.3).abs() < 1e-6);
        // Backing away stays free.
        let back = keep_distance(&me, Twist::new(-0.3, 0.0, 0.0), &near, r, 1.0);
        assert_eq!(back, Twist::new(-0.3, 0.0, 0.0));
        // Far away: untouched.
        let far = mate(3.0, 1.0, 0.0, 0.0);
        let t = keep_distance(&me, Twist::new(0.5, 0.0, 0.0), &far, r, 1.0);
        assert_eq!(t, Twist::new(0.5, 0.0, 0.0));
        // A teammate coming head-on leaves less room than a still one.
        let still = mate(1.6, 1.0, 0.0, 0.0);
        let coming = mate(1.6, 1.0, -0.4, 0.0);
        let a = keep_distance(&me, Twist::new(0.5, 0.0, 0.0), &still, r, 1.0);
        let b = keep_distance(&me, Twist::new(0.5, 0.0, 0.0), &coming, r, 1.0);
        assert!(b.vx_m_s < a.vx_m_s && a.vx_m_s < 0.5, "{a:?} {b:?}");
    }

    /// Two robots driving head-on, each knowing the other only as a body its IR ring
    /// sees (as standing still: their news lost or late), stop the guard's gap apart.
    #[test]
    fn two_robots_seeing_each_other_only_by_ir_stop_apart() {
        let (r, acc, dt) = (0.185f32, 1.0f32, 1.0f32 / 15.0);
        let mut a = (Pose2::new(1.0, 1.0, 0.0), 0.0f32);
        let mut b = (Pose2::new(2.2, 1.0, core::f32::consts::PI), 0.0f32);
        let mut least = f32::INFINITY;
        for _ in 0..60 {
            let seen = |other: &Pose2| Teammate {
                number: 0,
                x_m: other.x_m,
                y_m: other.y_m,
                vx_m_s: 0.0,
                vy_m_s: 0.0,
                silent: false,
            };
            let (sa, sb) = (seen(&b.0), seen(&a.0));
            for (me, other) in [(&mut a, sa), (&mut b, sb)] {
                let want = (me.1 + acc * dt).min(0.5);
                let t = keep_distance_from(&me.0, Twist::new(want, 0.0, 0.0), &[other], r, acc);
                // The drive brakes at most at its deceleration.
                me.1 = t.vx_m_s.max(me.1 - acc * dt).max(0.0);
                let (s, c) = me.0.phi_rad.sin_cos();
                me.0 = Pose2::new(
                    me.0.x_m + c * me.1 * dt,
                    me.0.y_m + s * me.1 * dt,
                    me.0.phi_rad,
                );
            }
            least = least.min((a.0.x_m - b.0.x_m).abs() - 2.0 * r);
        }
        // Each braking for a still body, each used the whole gap and they stopped 3.6 cm
        // apart (half the guard's gap); each keeping to its half, 6.8 cm.
        assert!(least > 0.05, "gap {least}");
    }

    /// A robot between two teammates: cutting the speed towards one must not add speed
    /// towards the other (seed 29 of the team game touched that way).
    #[test]
    fn the_guard_holds_between_two_teammates() {
        let r = 0.185;
        let me = Pose2::new(2.59, 1.856, core::f32::consts::FRAC_PI_2);
        let mates = [
            Some(Teammate {
                number: 3,
                x_m: 2.771,
                y_m: 2.196,
                vx_m_s: 0.0,
                vy_m_s: 0.0,
                silent: false,
            }),
            Some(Teammate {
                number: 2,
                x_m: 2.601,
                y_m: 1.400,
                vx_m_s: 0.361,
                vy_m_s: 0.088,
                silent: false,
            }),
        ];
        let t = keep_distance(&me, Twist::new(-0.045, -0.366, 0.0), &mates, r, 1.0);
        for m in mates.iter().flatten() {
            let (lx, ly) = me.to_local(m.x_m, m.y_m);
            let towards = (t.vx_m_s * lx + t.vy_m_s * ly) / lx.hypot(ly);
            assert!(
                towards < 0.05,
                "towards robot {}: {towards} ({t:?})",
                m.number
            );
        }
    }

    /// Two robots driving head-on at full speed, each guarding with the other's
    /// announcement of the cycle before, through the drive's acceleration limit: they
    /// stop apart.
    #[test]
    fn two_guarded_robots_head_on_never_touch() {
        let r = 0.185;
        let dt = 1.0 / 15.0;
        let limits = hal::limits::MotionLimits::ROBOTINO2;
        let mut poses = [Pose2::new(1.0, 1.0, 0.0), Pose2::new(3.0, 1.0, PI)];
        let mut twists = [Twist::ZERO; 2];
        let mut least = f32::INFINITY;
        use core::f32::consts::PI;
        for cycle in 0..15 * 10 {
            let reports: Vec<PoseReport> = (0..2)
                .map(|i| PoseReport::new(i as u8 + 1, cycle, poses[i], twists[i]))
                .collect();
            for i in 0..2 {
                let mut board = TeamBoard::default();
                board.hear(reports[1 - i]);
                let mates = board.teammates(cycle + 1, dt, &poses[i]);
                let want = keep_distance(&poses[i], Twist::new(0.5, 0.0, 0.0), &mates, r, 1.0);
                twists[i] = limits.clamp_acceleration(twists[i], want, dt);
            }
            for i in 0..2 {
                poses[i] = poses[i].advanced(twists[i], 0.0, dt);
            }
            least = least.min(poses[0].distance_to(&poses[1]) - 2.0 * r);
        }
        assert!(least > 0.02, "gap fell to {least}");
        assert!(least < 0.2, "they should come close: {least}");
    }
}
