//! The timeline picture of a process-level game (`game --svg FILE`): one lane per robot
//! with its skills as bars coloured by outcome (bumps as ticks), one lane per machine with
//! the lights the referee gave, and the score over time.

use std::fmt::Write;

use super::record::{Ending, GameRecord};

const LEFT: f64 = 90.0;
const WIDTH: f64 = 1000.0;
const LANE: f64 = 22.0;
const SCORE_H: f64 = 120.0;

fn skill_colour(ending: Ending) -> &'static str {
    match ending {
        Ending::Final => "#4caf50",
        Ending::Failed => "#e53935",
        Ending::Cut => "#9e9e9e",
    }
}

fn light_colour(light: &str) -> &'static str {
    match light {
        "green" => "#43a047",
        "yellow" => "#fdd835",
        "yellow-flashing" => "#ffb300",
        "red" => "#e53935",
        _ => "#bdbdbd",
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

pub fn render(g: &GameRecord) -> String {
    let span = g.game_seconds.max(g.game_time_s).max(1.0);
    let x = |t: f64| LEFT + t / span * WIDTH;
    let lights = g.machine_lights();
    let lanes = usize::from(g.robots) + lights.len();
    let score_top = 30.0 + lanes as f64 * LANE + 20.0;
    let height = score_top + SCORE_H + 40.0;
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{height}" font-family="sans-serif" font-size="11">"#,
        LEFT + WIDTH + 20.0
    );
    let _ = writeln!(
        out,
        r#"<text x="{LEFT}" y="16">seed {} · {} robot(s) · {} points · green FINAL, red FAILED, grey running at the end; black ticks: bumps</text>"#,
        g.seed, g.robots, g.score
    );
    // Time axis every 60 s.
    let mut t = 0.0;
    while t <= span {
        let _ = writeln!(
            out,
            "<line x1=\"{0:.1}\" y1=\"24\" x2=\"{0:.1}\" y2=\"{1:.1}\" stroke=\"#eee\"/><text x=\"{0:.1}\" y=\"{2:.1}\" text-anchor=\"middle\">{3}</text>",
            x(t),
            score_top + SCORE_H,
            score_top + SCORE_H + 14.0,
            t as u32
        );
        t += 60.0;
    }
    for robot in 1..=g.robots {
        let y = 30.0 + f64::from(robot - 1) * LANE;
        let _ = writeln!(
            out,
            r#"<text x="4" y="{:.1}">robot{robot}</text>"#,
            y + 14.0
        );
        for s in g.skills.iter().filter(|s| s.robot == robot) {
            let w = (x(s.end_s) - x(s.start_s)).max(1.0);
            let _ = writeln!(
                out,
                r##"<rect x="{:.1}" y="{y:.1}" width="{w:.1}" height="{:.1}" fill="{}" stroke="#fff" stroke-width="0.5"><title>{}</title></rect>"##,
                x(s.start_s),
                LANE - 4.0,
                skill_colour(s.ending),
                escape(&format!(
                    "t={:.1}..{:.1} {} {} holding {}: {}",
                    s.start_s, s.end_s, s.name, s.target, s.holding, s.outcome
                ))
            );
        }
        for (t, _, with) in g.bumps.iter().filter(|b| b.1 == robot) {
            let _ = writeln!(
                out,
                r#"<line x1="{0:.1}" y1="{1:.1}" x2="{0:.1}" y2="{2:.1}" stroke="black" stroke-width="1.5"><title>bump {3} at {4:.1} s</title></line>"#,
                x(*t),
                y - 2.0,
                y + LANE - 2.0,
                escape(with),
                t
            );
        }
    }
    for (i, (machine, changes)) in lights.iter().enumerate() {
        let y = 30.0 + (usize::from(g.robots) + i) as f64 * LANE;
        let _ = writeln!(
            out,
            r#"<text x="4" y="{:.1}">{machine} light</text>"#,
            y + 14.0
        );
        for (k, (from, light)) in changes.iter().enumerate() {
            let to = changes.get(k + 1).map_or(g.game_time_s, |c| c.0);
            let _ = writeln!(
                out,
                r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="{}"><title>{machine} {light} from {from:.1} s</title></rect>"#,
                x(*from),
                y + 4.0,
                (x(to) - x(*from)).max(1.0),
                LANE - 10.0,
                light_colour(light)
            );
        }
    }
    // Score over time: a step line through the referee's answers.
    let max_score = g.referee.iter().map(|e| e.score).max().unwrap_or(0).max(1) as f64;
    let sy = |s: i64| score_top + SCORE_H - s as f64 / max_score * SCORE_H;
    let mut points = format!("{:.1},{:.1}", x(0.0), sy(0));
    let mut last = 0;
    for e in &g.referee {
        if e.score != last {
            let _ = write!(
                points,
                " {0:.1},{1:.1} {0:.1},{2:.1}",
                x(e.time_s),
                sy(last),
                sy(e.score)
            );
            last = e.score;
        }
    }
    let _ = write!(points, " {:.1},{:.1}", x(g.game_time_s), sy(last));
    let _ = writeln!(
        out,
        r#"<text x="4" y="{:.1}">score</text><text x="4" y="{:.1}">{}</text>"#,
        score_top + 12.0,
        score_top + 26.0,
        max_score as i64
    );
    let _ = writeln!(
        out,
        r##"<polyline points="{points}" fill="none" stroke="#1e88e5" stroke-width="2"/>"##
    );
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_a_lane_per_robot_and_machine_and_a_score_line() {
        let sim: Vec<String> = [
            "robotino-sim: cycle=300 referee t=20.0 robot=1 load M1 S0 -> ok light=yellow puck=NONE wait=2.0 score=0",
            "robotino-sim: cycle=600 referee t=40.0 robot=1 deliver D1 P1 -> ok light=none puck=NONE wait=0.0 score=10",
            "robotino-sim: done cycles=900 game_time_s=60.0 score=10 bumps=0 robot_contacts=0 wall_ms=1",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let a: Vec<String> = [
            "robotino-agent run: cycle=2 start GetS0 (skill-request 1 get-s0 INS holding NONE)",
            "robotino-agent run: cycle=180 end GetS0 Failed(Bumper) bumper",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let g = GameRecord::parse(0, 60.0, &sim, &[a.clone(), a]);
        let svg = render(&g);
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains(">robot2</text>"));
        assert!(svg.contains(">M1 light</text>"));
        assert_eq!(svg.matches("fill=\"#e53935\"").count(), 2);
        assert!(svg.contains("<polyline"));
    }
}
