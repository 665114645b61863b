//! What a frame did besides its passes: the allocations it made and the pipeline variants it
//! bound, logged while it is recorded on this thread (`frame.memory_bytes`, and the test that
//! every pass ran the variant its plan asked for).

use std::cell::RefCell;

/// What a frame did besides its passes, logged while it is recorded on this thread.
#[derive(Clone, Debug, Default)]
pub struct FrameLog {
    /// (label, bytes summed over the buffers and targets with that label that the frame
    /// used, created now or kept from earlier frames), in first-use order (`frame.memory_bytes`).
    pub uses: Vec<(String, u64)>,
    /// The same for what the frame created (`frame.settings["allocated_bytes"]` sums it).
    pub allocations: Vec<(String, u64)>,
    /// Every pipeline variant the frame bound: (shader path, entry point, override flags).
    pub variants: Vec<(String, String, Vec<(&'static str, bool)>)>,
    /// Every pass that ran (GPU passes as they begin, CPU work such as a BVH build as it is
    /// done), once each, in first-run order.
    pub passes: Vec<String>,
    /// Bind groups the frame had to make (0 when every one was kept from an earlier frame).
    pub bind_groups_created: u64,
    /// What CPU work of the frame measured about itself (a BVH build's time and size), for
    /// `frame.settings`, in the order noted.
    pub settings: Vec<(String, crate::Setting)>,
}

thread_local! {
    /// The frame being recorded on this thread logs here (see [`log_frame`]).
    static FRAME_LOG: RefCell<Option<FrameLog>> = const { RefCell::new(None) };
}

fn with_frame_log(f: impl FnOnce(&mut FrameLog)) {
    FRAME_LOG.with(|log| {
        if let Some(log) = log.borrow_mut().as_mut() {
            f(log);
        }
    });
}

fn add(list: &mut Vec<(String, u64)>, label: &str, bytes: u64) {
    match list.iter_mut().find(|(l, _)| l == label) {
        Some((_, b)) => *b += bytes,
        None => list.push((label.to_string(), bytes)),
    }
}

/// Notes that the frame created `bytes` for `label` (a no-op outside [`log_frame`]).
pub fn note_allocation(label: &str, bytes: u64) {
    with_frame_log(|log| add(&mut log.allocations, label, bytes));
}

/// Notes that the frame made a bind group (a no-op outside [`log_frame`]).
pub fn note_bind_group_created() {
    with_frame_log(|log| log.bind_groups_created += 1);
}

/// Notes that the frame used `bytes` for `label`, new or kept (a no-op outside [`log_frame`]).
pub fn note_use(label: &str, bytes: u64) {
    with_frame_log(|log| add(&mut log.uses, label, bytes));
}

/// Notes that the frame bound this pipeline variant (a no-op outside [`log_frame`]).
pub fn note_variant(shader: &str, entry: &str, flags: &[(&'static str, bool)]) {
    with_frame_log(|log| {
        if !log.variants.iter().any(|(s, e, f)| s == shader && e == entry && f.as_slice() == flags) {
            log.variants.push((shader.to_string(), entry.to_string(), flags.to_vec()));
        }
    });
}

/// Notes that pass `name` ran (a no-op outside [`log_frame`]).
pub fn note_pass(name: &str) {
    with_frame_log(|log| {
        if !log.passes.iter().any(|p| p == name) {
            log.passes.push(name.to_string());
        }
    });
}

/// Notes a `frame.settings` row measured by CPU work of the frame (a no-op outside
/// [`log_frame`]); a second note of the same name replaces the first.
pub fn note_setting(name: &str, value: crate::Setting) {
    with_frame_log(|log| match log.settings.iter_mut().find(|(n, _)| n == name) {
        Some(row) => row.1 = value,
        None => log.settings.push((name.to_string(), value)),
    });
}

/// Runs `f` and returns what it logged: the allocations made through [`storage_buffer`] and
/// the other noted targets, and the pipeline variants bound.
pub fn log_frame<T>(f: impl FnOnce() -> T) -> (T, FrameLog) {
    let outer = FRAME_LOG.with(|log| log.borrow_mut().replace(FrameLog::default()));
    let value = f();
    let logged = FRAME_LOG.with(|log| std::mem::replace(&mut *log.borrow_mut(), outer)).unwrap_or_default();
    (value, logged)
}
