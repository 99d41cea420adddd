//! Receive monitor: per message, timeouts, rolling-counter repeats and jumps, checksum and length
//! faults, a state in the spirit of AUTOSAR E2E's state machine, statistics, and the protocol's
//! fault codes — without allocation, from caller-supplied millisecond times (a wrapping 32-bit
//! tick). The rules are those of canspec's reference monitor (`generator/canspec/runtime/monitor.py`),
//! which the C and Python monitors follow too; the shared sequence vectors test all three:
//!
//! - A frame is looked up by its ID and ID format; an unknown one is counted and touches nothing.
//! - A message with a timeout is supervised from [`Monitor::start`] or from its first accepted
//!   frame, and times out when more than its timeout has passed since its last accepted frame
//!   (at exactly the timeout it has not): found by [`Monitor::check`], or by [`Monitor::feed`]
//!   for the message's own frame before judging it.
//! - A frame of the wrong length, or whose checksum byte is not the XOR of the bytes it covers,
//!   is rejected. Counter delta = (counter − stored) mod 2^bits: 0 is a repeat (rejected);
//!   1..=1+tolerance is in sequence; more is a jump, accepted: the sequence restarts from it. The
//!   first frame, and the first after a timeout, are not compared (a repeat still is).
//! - A rejected frame changes neither the stored counter nor the timeout's reference time; an
//!   accepted frame ends a timeout and a checksum fault.
//! - State: `NoData` until the first frame; every fault makes it `Invalid`; `valid_after`
//!   accepted frames in a row without a fault make it `Valid` (`Init` until then when it had no data).
//! - Fault codes per table: the lowest of the checksum codes of messages whose last frame failed
//!   the checksum and the timeout code while any message is timed out; else the table's `none`.
//! - Counts saturate at `u32::MAX`.

/// A rolling counter: `length` bits from bit `start` of the frame read as one integer,
/// little-endian (an Intel counter) or big-endian (a Motorola one).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CounterRule {
    /// Its least significant bit in that integer.
    pub start: u32,
    /// Bits (1..=8).
    pub length: u32,
    /// The frame is read big-endian.
    pub big_endian: bool,
}

impl CounterRule {
    /// The counter in a frame of the message's length.
    pub fn read(&self, data: &[u8]) -> u8 {
        let first = (self.start / 8) as usize; // the integer's byte holding the counter's LSB
        let byte = |k: usize| {
            let index = if self.big_endian { data.len().checked_sub(1 + first + k) } else { Some(first + k) };
            index.and_then(|i| data.get(i)).map_or(0, |&b| u16::from(b))
        };
        let pair = byte(0) | byte(1) << 8;
        ((pair >> (self.start % 8)) & ((1 << self.length) - 1)) as u8
    }
}

/// An XOR checksum in byte `byte`: the XOR of the bytes `covers` selects.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChecksumRule {
    /// The checksum's byte.
    pub byte: usize,
    /// The covered bytes: bit i is byte i (frames of up to 64 bytes).
    pub covers: u64,
}

impl ChecksumRule {
    /// The XOR of the covered bytes of a frame.
    pub fn expected(&self, data: &[u8]) -> u8 {
        data.iter().enumerate().filter(|&(i, _)| i < 64 && self.covers >> i & 1 == 1).fold(0, |x, (_, &b)| x ^ b)
    }
}

/// What the monitor checks of one message.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rule {
    /// Message name in the spec.
    pub name: &'static str,
    /// Identifier.
    pub frame_id: u32,
    /// 29-bit identifier.
    pub extended: bool,
    /// Data length code.
    pub dlc: usize,
    /// `None`: no timeout supervision (event-driven).
    pub timeout_ms: Option<u32>,
    /// The rolling counter, if any.
    pub counter: Option<CounterRule>,
    /// The checksum, if any.
    pub checksum: Option<ChecksumRule>,
}

/// A value table of fault codes the monitor reports in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FaultTable {
    /// The table's name in the spec.
    pub name: &'static str,
    /// No fault.
    pub none: i64,
    /// A message timed out.
    pub timeout: i64,
    /// (index of the message's rule, code) for a checksum failure of that message.
    pub checksum: &'static [(usize, i64)],
}

/// A message's receive state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum State {
    /// Nothing received yet.
    NoData,
    /// Receiving, not yet `valid_after` good frames in a row.
    Init,
    /// Valid: use its values.
    Valid,
    /// A fault; valid again after `valid_after` good frames in a row.
    Invalid,
}

/// What can be wrong with a frame or a message.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Fault {
    /// No message has the frame's ID in its ID format.
    UnknownId,
    /// The frame's length differs from the DLC.
    Length,
    /// The checksum byte does not match.
    Checksum,
    /// The counter did not change.
    CounterRepeat,
    /// The counter moved further than the tolerance allows.
    CounterJump,
    /// The message's timeout ran out.
    Timeout,
}

/// What one frame did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameEvent {
    /// The message's rule index (`None`: unknown ID).
    pub message: Option<usize>,
    /// Timeout (ran out before this frame): listed first by [`FrameEvent::faults`].
    pub timed_out: bool,
    /// The frame's own fault, if any.
    pub fault: Option<Fault>,
    /// Intact and new: its data count (see the state).
    pub accepted: bool,
    /// The message's state after the frame.
    pub state: Option<State>,
    /// Its state before.
    pub previous_state: Option<State>,
    /// The frame's counter (`None`: no counter, or the frame is not intact).
    pub counter: Option<u8>,
    /// The counter's step from the stored counter (`None`: not compared).
    pub counter_delta: Option<u32>,
    /// `None`: no checksum, or the length is wrong.
    pub checksum_ok: Option<bool>,
    /// Milliseconds since the message's previous frame (`None`: its first).
    pub gap_ms: Option<u32>,
    /// `Invalid` → `Valid` with this frame.
    pub recovered: bool,
}

impl FrameEvent {
    /// The faults in order: a timeout first, then the frame's own.
    pub fn faults(&self) -> impl Iterator<Item = Fault> {
        self.timed_out.then_some(Fault::Timeout).into_iter().chain(self.fault)
    }
}

/// Per-message counts (saturating) and the gaps between its frames.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Frames received.
    pub frames: u32,
    /// Frames accepted.
    pub accepted: u32,
    /// Frames of the wrong length.
    pub length_errors: u32,
    /// Frames with a wrong checksum.
    pub checksum_errors: u32,
    /// Counter repeats.
    pub counter_repeats: u32,
    /// Counter jumps beyond the tolerance.
    pub counter_jumps: u32,
    /// Frames missing in counter steps within the tolerance.
    pub lost_frames: u32,
    /// Timeouts.
    pub timeouts: u32,
    /// Shortest gap between two frames.
    pub min_gap_ms: Option<u32>,
    /// Longest gap between two frames.
    pub max_gap_ms: Option<u32>,
    /// Sum of the gaps.
    pub gap_total_ms: u64,
    /// Gaps measured.
    pub gaps: u32,
}

#[derive(Clone, Copy, Debug)]
struct Track {
    state: State,
    good_run: u32,
    armed: bool,
    reference_ms: u32,
    timed_out: bool,
    checksum_failed: bool,
    counter: Option<u8>,
    last_frame_ms: Option<u32>,
    stats: Stats,
}

impl Track {
    const NEW: Self = Self {
        state: State::NoData,
        good_run: 0,
        armed: false,
        reference_ms: 0,
        timed_out: false,
        checksum_failed: false,
        counter: None,
        last_frame_ms: None,
        stats: Stats {
            frames: 0,
            accepted: 0,
            length_errors: 0,
            checksum_errors: 0,
            counter_repeats: 0,
            counter_jumps: 0,
            lost_frames: 0,
            timeouts: 0,
            min_gap_ms: None,
            max_gap_ms: None,
            gap_total_ms: 0,
            gaps: 0,
        },
    };

    fn fail(&mut self) {
        self.state = State::Invalid;
        self.good_run = 0;
    }
}

/// The receive monitor of `N` messages (see the module documentation).
#[derive(Clone, Debug)]
pub struct Monitor<const N: usize> {
    rules: [Rule; N],
    tables: &'static [FaultTable],
    tracks: [Track; N],
    unknown_frames: u32,
    counter_tolerance: u32,
    valid_after: u32,
}

impl<const N: usize> Monitor<N> {
    /// A monitor of these rules (`valid_after` at least 1), reporting in these fault tables.
    pub const fn new(rules: [Rule; N], tables: &'static [FaultTable], counter_tolerance: u32, valid_after: u32) -> Self {
        Self {
            rules,
            tables,
            tracks: [Track::NEW; N],
            unknown_frames: 0,
            counter_tolerance,
            valid_after: if valid_after == 0 { 1 } else { valid_after },
        }
    }

    /// The rules.
    pub const fn rules(&self) -> &[Rule; N] {
        &self.rules
    }

    /// The index of the message named `name`.
    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.rules.iter().position(|r| r.name == name)
    }

    /// A message's state.
    pub fn state(&self, message: usize) -> State {
        self.tracks[message].state
    }

    /// Whether a message is timed out.
    pub fn timed_out(&self, message: usize) -> bool {
        self.tracks[message].timed_out
    }

    /// A message's statistics.
    pub fn stats(&self, message: usize) -> &Stats {
        &self.tracks[message].stats
    }

    /// Frames of unknown IDs.
    pub const fn unknown_frames(&self) -> u32 {
        self.unknown_frames
    }

    /// The fault tables.
    pub const fn fault_tables(&self) -> &'static [FaultTable] {
        self.tables
    }

    /// The code of fault table `table` now.
    pub fn fault_code(&self, table: usize) -> i64 {
        let t = &self.tables[table];
        let checksum = t.checksum.iter().filter(|(m, _)| self.tracks[*m].checksum_failed).map(|&(_, code)| code);
        let timeout = self.tracks.iter().any(|tr| tr.timed_out).then_some(t.timeout);
        checksum.chain(timeout).min().unwrap_or(t.none)
    }

    /// Supervise message `message`'s timeout from `now_ms` on.
    pub fn start(&mut self, message: usize, now_ms: u32) {
        let track = &mut self.tracks[message];
        track.armed = true;
        track.reference_ms = now_ms;
        track.timed_out = false;
    }

    /// Supervise every message's timeout from `now_ms` on.
    pub fn start_all(&mut self, now_ms: u32) {
        for message in 0..N {
            self.start(message, now_ms);
        }
    }

    /// Time out the messages whose timeout has run out at `now_ms`, calling `timed_out` with
    /// each one's index (once per timeout); returns how many.
    pub fn check(&mut self, now_ms: u32, mut timed_out: impl FnMut(usize)) -> usize {
        let mut count = 0;
        for message in 0..N {
            if self.expire(message, now_ms) {
                timed_out(message);
                count += 1;
            }
        }
        count
    }

    fn expire(&mut self, message: usize, now_ms: u32) -> bool {
        let (rule, track) = (&self.rules[message], &mut self.tracks[message]);
        match rule.timeout_ms {
            Some(limit) if track.armed && !track.timed_out && now_ms.wrapping_sub(track.reference_ms) > limit => {
                track.timed_out = true;
                track.stats.timeouts = track.stats.timeouts.saturating_add(1);
                track.fail();
                true
            }
            _ => false,
        }
    }

    /// Judge one received frame at `now_ms`.
    pub fn feed(&mut self, now_ms: u32, frame_id: u32, extended: bool, data: &[u8]) -> FrameEvent {
        let Some(message) = self.rules.iter().position(|r| r.frame_id == frame_id && r.extended == extended) else {
            self.unknown_frames = self.unknown_frames.saturating_add(1);
            return FrameEvent {
                message: None,
                timed_out: false,
                fault: Some(Fault::UnknownId),
                accepted: false,
                state: None,
                previous_state: None,
                counter: None,
                counter_delta: None,
                checksum_ok: None,
                gap_ms: None,
                recovered: false,
            };
        };
        let previous = self.tracks[message].state;
        let gap = self.tracks[message].last_frame_ms.map(|last| now_ms.wrapping_sub(last));
        count_frame(&mut self.tracks[message].stats, gap);
        self.tracks[message].last_frame_ms = Some(now_ms);
        let timed_out = self.expire(message, now_ms);
        let (fault, checksum_ok, counter, delta) = self.judge(message, data);
        let accepted = matches!(fault, None | Some(Fault::CounterJump));
        if accepted {
            self.accept(message, now_ms, counter, fault.is_some());
        }
        let state = self.tracks[message].state;
        FrameEvent {
            message: Some(message),
            timed_out,
            fault,
            accepted,
            state: Some(state),
            previous_state: Some(previous),
            counter,
            counter_delta: delta,
            checksum_ok,
            gap_ms: gap,
            recovered: previous == State::Invalid && state == State::Valid,
        }
    }

    fn judge(&mut self, message: usize, data: &[u8]) -> (Option<Fault>, Option<bool>, Option<u8>, Option<u32>) {
        let (rule, track) = (&self.rules[message], &mut self.tracks[message]);
        if data.len() != rule.dlc {
            track.stats.length_errors = track.stats.length_errors.saturating_add(1);
            track.fail();
            return (Some(Fault::Length), None, None, None);
        }
        let mut checksum_ok = None;
        if let Some(ck) = rule.checksum {
            let ok = ck.expected(data) == data[ck.byte];
            checksum_ok = Some(ok);
            if !ok {
                track.stats.checksum_errors = track.stats.checksum_errors.saturating_add(1);
                track.checksum_failed = true;
                track.fail();
                return (Some(Fault::Checksum), checksum_ok, None, None);
            }
        }
        let Some(c) = rule.counter else {
            return (None, checksum_ok, None, None);
        };
        let modulo = 1u32 << c.length;
        let counter = c.read(data);
        let Some(stored) = track.counter else {
            return (None, checksum_ok, Some(counter), None);
        };
        let delta = (u32::from(counter) + modulo - u32::from(stored)) % modulo;
        if delta == 0 {
            track.stats.counter_repeats = track.stats.counter_repeats.saturating_add(1);
            track.fail();
            return (Some(Fault::CounterRepeat), checksum_ok, Some(counter), Some(delta));
        }
        if track.timed_out {
            return (None, checksum_ok, Some(counter), Some(delta)); // the sequence restarts after a timeout
        }
        if delta > 1 + self.counter_tolerance {
            track.stats.counter_jumps = track.stats.counter_jumps.saturating_add(1);
            return (Some(Fault::CounterJump), checksum_ok, Some(counter), Some(delta));
        }
        track.stats.lost_frames = track.stats.lost_frames.saturating_add(delta - 1);
        (None, checksum_ok, Some(counter), Some(delta))
    }

    fn accept(&mut self, message: usize, now_ms: u32, counter: Option<u8>, jumped: bool) {
        let valid_after = self.valid_after;
        let track = &mut self.tracks[message];
        track.stats.accepted = track.stats.accepted.saturating_add(1);
        track.armed = true;
        track.reference_ms = now_ms;
        track.timed_out = false;
        track.checksum_failed = false;
        if counter.is_some() {
            track.counter = counter;
        }
        if jumped {
            track.fail();
            return;
        }
        track.good_run = (track.good_run + 1).min(valid_after);
        if track.good_run >= valid_after {
            track.state = State::Valid;
        } else if track.state == State::NoData {
            track.state = State::Init;
        }
    }
}

fn count_frame(stats: &mut Stats, gap: Option<u32>) {
    stats.frames = stats.frames.saturating_add(1);
    if let Some(gap) = gap {
        stats.gaps = stats.gaps.saturating_add(1);
        stats.gap_total_ms = stats.gap_total_ms.saturating_add(u64::from(gap));
        stats.min_gap_ms = Some(stats.min_gap_ms.map_or(gap, |m| m.min(gap)));
        stats.max_gap_ms = Some(stats.max_gap_ms.map_or(gap, |m| m.max(gap)));
    }
}
