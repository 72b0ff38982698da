//! Join tests over slots that follow a multislot, slots before one, multislot
//! elements and ordered facts' fields, with facts whose multislots hold elements
//! (so their slots do not lie one cell each). The host compiles such tests into plans
//! that read fixed offsets where a template allows (`rete::plan`); the firings must
//! be CLIPS's. Expected output: CLIPS 6.30, `clips -f2` of the same program with
//! `(reset)` and `(run)`.
#![cfg(feature = "parser")]

use agent_core::{Host, SmallEngine};

#[derive(Default)]
struct Capture(String);

impl Host for Capture {
    fn write_str(&mut self, _router: &str, text: &str) {
        self.0.push_str(text);
    }
}

const PROGRAM: &str = r#"
(deftemplate a (multislot m) (slot x) (slot y))
(deftemplate b (slot x) (multislot m) (slot y))
(deftemplate c (slot x) (slot y))
(defrule after-multi
   (c (x ?x) (y ?y))
   (a (x ?ax&?x|?y) (y ?ay&~?x))
   =>
   (printout t "after-multi " ?x " " ?y " " ?ax " " ?ay crlf))
(defrule before-multi
   (c (x ?x) (y ?y))
   (b (x ?bx&?x|?y) (y ?by&~?bx))
   =>
   (printout t "before-multi " ?x " " ?y " " ?bx " " ?by crlf))
(defrule before-only
   (c (x ?x) (y ?y))
   (b (x ?bx&?x|?y) (m $? ?last))
   =>
   (printout t "before-only " ?x " " ?y " " ?bx " " ?last crlf))
(defrule elements
   (b (x ?bx) (m ?e1 ?e2 $?))
   (c (x ?cx&?e1|?e2) (y ?cy&:(> ?cy ?bx)))
   =>
   (printout t "elements " ?bx " " ?e1 " " ?e2 " " ?cx " " ?cy crlf))
(defrule ordered
   (t ?p ?q ?r)
   (c (x ?x&?p|?r) (y ?y&~?q))
   (not (b (x ?y) (y ?x|?p)))
   =>
   (printout t "ordered " ?p " " ?q " " ?r " " ?x " " ?y crlf))
(deffacts f
   (c (x 1) (y 2))
   (c (x 2) (y 3))
   (c (x 3) (y 1))
   (a (m) (x 1) (y 5))
   (a (m 9 9 9) (x 2) (y 3))
   (a (m 1) (x 3) (y 3))
   (b (x 1) (m) (y 2))
   (b (x 2) (m 7 7 7 7) (y 2))
   (b (x 3) (m 2 3) (y 4))
   (b (x 0) (m 1 3 5) (y 9))
   (t 1 2 3)
   (t 3 1 2)
   (t 2 3 1))
"#;

const CLIPS_OUTPUT: &str = "\
ordered 3 1 2 2 3\n\
ordered 1 2 3 3 1\n\
elements 0 1 3 3 1\n\
elements 0 1 3 1 2\n\
before-multi 2 3 3 4\n\
before-multi 3 1 3 4\n\
before-only 2 3 3 3\n\
before-only 3 1 3 3\n\
before-only 1 2 2 7\n\
before-only 2 3 2 7\n\
before-multi 1 2 1 2\n\
before-multi 3 1 1 2\n\
after-multi 2 3 3 3\n\
after-multi 1 2 2 3\n\
after-multi 2 3 2 3\n\
after-multi 1 2 1 5\n\
after-multi 3 1 1 5\n\
";

#[test]
fn join_tests_read_slots_around_multislots_as_clips() {
    let mut engine = Box::new(SmallEngine::new());
    let mut host = Capture::default();
    engine
        .load_str(&mut host, "plans.clp", PROGRAM)
        .expect("the program loads");
    engine.reset(&mut host).expect("reset");
    let fired = engine.run(&mut host, None).expect("run");
    assert_eq!(host.0, CLIPS_OUTPUT);
    assert_eq!(fired, 17);
}
