//! The team's claims over Zenoh: three robots, each with
//! its own engine and its own Zenoh session on explicit TCP endpoints on this host,
//! reach each other only over Zenoh. Our fault proxy (`FaultyNet`) sits at each
//! receiver and loses 10 % of the messages and delays the rest up to 2 s of game time;
//! over the game no resource is held by two robots at once.
//!
//! `cd team-link && cargo test`

use std::time::Duration;

use host_shim::team::{FaultyNet, LinkFaults, TeamMember};
use rules::setup::SplitMix64;
use team_link::ZenohLink;

const ROBOTS: u8 = 3;
const RESOURCES: [&str; 2] = ["M1", "INS"];
const STEP: f64 = 0.5;
const GAME: f64 = 60.0;

fn on_big_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(f)
        .expect("spawning the test thread")
        .join()
        .expect("the test thread panicked")
}

#[test]
fn claims_over_zenoh_with_loss_and_delay_are_never_double() {
    on_big_stack(|| {
        // Ports from the process id, so parallel runs on one host do not collide.
        let base = 20_000 + (std::process::id() % 20_000) as u16;
        let endpoint = |r: u8| format!("tcp/127.0.0.1:{}", base + u16::from(r));
        let links: Vec<ZenohLink> = (1..=ROBOTS)
            .map(|r| {
                // Each robot listens on its own port and connects to the lower ones.
                let connect: Vec<String> = (1..r).map(endpoint).collect();
                ZenohLink::open(r, "test-team", &[endpoint(r)], &connect)
                    .unwrap_or_else(|e| panic!("robot {r}: {e}"))
            })
            .collect();
        std::thread::sleep(Duration::from_millis(500)); // sessions meet
        let mut members: Vec<TeamMember> = (0..ROBOTS)
            .map(|_| TeamMember::new(&[], None).unwrap_or_else(|e| panic!("{e}")))
            .collect();
        for (i, m) in members.iter_mut().enumerate() {
            m.start(i as u8 + 1, ROBOTS, 0.0, &[])
                .unwrap_or_else(|e| panic!("{e}"));
        }
        let faults = LinkFaults {
            loss_percent: 10,
            delay_min: 0.0,
            delay_max: 2.0,
            dup_percent: 0,
        };
        let mut proxies: Vec<FaultyNet> = (0..ROBOTS)
            .map(|r| FaultyNet::new(faults, u64::from(r)))
            .collect();
        let mut rng = SplitMix64::new(5);
        let mut holding: Vec<Option<(usize, f64)>> = vec![None; ROBOTS as usize];
        let (mut sent_total, mut received_total) = (0usize, 0usize);
        let mut held_steps = 0;
        let mut t = 0.0;
        while t < GAME {
            let mut sent_now = 0;
            for i in 0..members.len() {
                let m = &mut members[i];
                for (_, msg) in proxies[i].arrived(t) {
                    m.receive(&msg).unwrap_or_else(|e| panic!("{e}"));
                }
                m.set_time(t).unwrap_or_else(|e| panic!("{e}"));
                match holding[i] {
                    None if m.wants().is_empty() => {
                        let r = rng.below(RESOURCES.len() as u64) as usize;
                        m.want(RESOURCES[r]).unwrap_or_else(|e| panic!("{e}"));
                    }
                    Some((r, until)) if t >= until => {
                        m.unwant(RESOURCES[r]).unwrap_or_else(|e| panic!("{e}"));
                        holding[i] = None;
                    }
                    _ => {}
                }
                m.run().unwrap_or_else(|e| panic!("{e}"));
                if holding[i].is_none() {
                    if let Some(r) = RESOURCES.iter().position(|x| m.holds(x)) {
                        holding[i] = Some((r, t + 1.0 + 5.0 * (rng.below(100) as f64 / 100.0)));
                    }
                }
                for msg in m.outbox().unwrap_or_else(|e| panic!("{e}")) {
                    links[i].send(&msg).unwrap_or_else(|e| panic!("{e}"));
                    sent_now += 1;
                }
            }
            sent_total += sent_now;
            // Wait until every teammate has every message sent this step (Zenoh is
            // reliable over TCP), then hand them to the fault proxies at game time t.
            let expected = sent_now * (ROBOTS as usize - 1);
            let mut got = 0;
            let deadline = std::time::Instant::now() + Duration::from_secs(10);
            while got < expected && std::time::Instant::now() < deadline {
                for (i, link) in links.iter().enumerate() {
                    for msg in link
                        .receive(Duration::from_millis(5))
                        .unwrap_or_else(|e| panic!("{e}"))
                    {
                        proxies[i].send(&msg, t, [i as u8 + 1]);
                        got += 1;
                    }
                }
            }
            assert_eq!(got, expected, "Zenoh lost messages at {t} s");
            received_total += got;
            for x in RESOURCES {
                let holders: Vec<usize> = (0..members.len())
                    .filter(|&i| members[i].holds(x))
                    .collect();
                assert!(
                    holders.len() <= 1,
                    "{x} held by robots {holders:?} at {t} s"
                );
                held_steps += holders.len();
            }
            t += STEP;
        }
        assert!(sent_total > 50, "only {sent_total} messages");
        assert_eq!(received_total, sent_total * (ROBOTS as usize - 1));
        assert!(
            held_steps > 20,
            "resources were held in only {held_steps} steps"
        );
    });
}
