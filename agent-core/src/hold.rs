//! Holding back watch traces while an operation may still be undone.
//!
//! An assert or modify prints its `(watch facts)` / `(watch activations)` lines as it
//! goes, the way CLIPS interleaves them. If the network then runs out of room the
//! operation is undone, and lines about a fact that never came (or a retract that
//! was taken back) would be wrong. So the traces of such an operation go to a small
//! buffer first: they go out when it succeeds and are dropped when it fails.
//!
//! The buffer is bounded (`HOLD_BYTES`). An operation tracing more than that, or
//! writing anything else meanwhile (an error message), sends what is held out at
//! once and passes its further traces straight through, so the output order stays
//! CLIPS's; only such a (large) failed operation still shows its lines up to the
//! failure.

use core::fmt;

use crate::engine::Core;
use crate::host::{router, Host};
use crate::value::TextBuf;

/// Bytes of watch traces one operation can hold back (some ten lines).
pub const HOLD_BYTES: usize = 512;

pub struct TraceHold {
    /// Nesting depth of open holds (an assert inside a modify); 0: none.
    pub depth: u8,
    /// The held traces went out already: the rest passes straight through.
    pub spilled: bool,
    pub buf: TextBuf<HOLD_BYTES>,
}

impl TraceHold {
    pub const EMPTY: TraceHold = TraceHold {
        depth: 0,
        spilled: false,
        buf: TextBuf::new(),
    };

    /// Sends what is held out; further traces of this hold pass straight through.
    fn spill(&mut self, host: &mut dyn Host) {
        if !self.buf.is_empty() {
            host.write_str(router::WTRACE, self.buf.as_str());
            self.buf.clear();
        }
        self.spilled = true;
    }
}

/// Writes watch traces: into the hold while one is open, else to the host.
pub struct TraceWriter<'h> {
    pub host: &'h mut dyn Host,
    pub hold: &'h mut TraceHold,
}

impl fmt::Write for TraceWriter<'_> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let h = &mut *self.hold;
        if h.depth > 0 && !h.spilled {
            if h.buf.len() + s.len() <= HOLD_BYTES {
                return h.buf.write_str(s);
            }
            h.spill(self.host);
        }
        self.host.write_str(router::WTRACE, s);
        Ok(())
    }
}

impl Core<'_> {
    /// Opens a hold (nested holds share the outermost one's fate).
    pub(crate) fn hold_traces(&mut self) {
        self.st.net.hold.depth = self.st.net.hold.depth.saturating_add(1);
    }

    /// Closes a hold. The outermost one sends the held traces out when the
    /// operation succeeded (`keep`) and drops them when it was undone.
    /// (Inlined on the host: every assert and retract closes one, mostly with nothing
    /// held.)
    #[cfg_attr(feature = "host-speedups", inline(always))]
    pub(crate) fn release_traces(&mut self, keep: bool) {
        let h = &mut self.st.net.hold;
        h.depth = h.depth.saturating_sub(1);
        if h.depth > 0 {
            return;
        }
        h.spilled = false;
        if !h.buf.is_empty() {
            self.send_held_traces(keep);
        }
    }

    /// Sends the held traces out if `keep`, and forgets them.
    #[cfg_attr(feature = "host-speedups", inline(never))]
    fn send_held_traces(&mut self, keep: bool) {
        let h = &mut self.st.net.hold;
        if keep {
            self.host.write_str(router::WTRACE, h.buf.as_str());
        }
        h.buf.clear();
    }

    /// Another write while traces are held: they go out first, to keep the order.
    pub(crate) fn spill_traces(&mut self) {
        if self.st.net.hold.depth > 0 && !self.st.net.hold.spilled {
            self.st.net.hold.spill(&mut *self.host);
        }
    }
}
