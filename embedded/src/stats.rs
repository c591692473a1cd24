//! Per-step instruction counts and their summary (median, 99th percentile and max) for one
//! kind of step.

/// Most steps one [`StepCounts`] records.
pub const MAX_STEPS: usize = 1024;

/// Instruction counts of the steps of one kind (active or resting), in step order.
pub struct StepCounts {
    /// `(frame, instructions)` of each recorded step.
    steps: [(u32, u64); MAX_STEPS],
    len: usize,
}

/// Median, 99th percentile and maximum of a [`StepCounts`] (instructions), with the number
/// of steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Summary {
    /// Steps counted.
    pub steps: usize,
    /// Median instructions per step (the lower middle for an even count; 0 with no step).
    pub median: u64,
    /// 99th percentile by nearest rank: the $\lceil 0.99 n \rceil$-th smallest of the $n$
    /// steps (0 with no step).
    pub p99: u64,
    /// Most instructions in one step (0 with no step).
    pub max: u64,
    /// Frame of the step with the most instructions.
    pub max_frame: u32,
    /// Instructions of all the steps.
    pub total: u64,
}

impl StepCounts {
    /// No steps yet.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            steps: [(0, 0); MAX_STEPS],
            len: 0,
        }
    }

    /// Records the step of `frame` and its instructions; `false` (nothing recorded) when
    /// [`MAX_STEPS`] are already recorded.
    pub fn push(&mut self, frame: u32, instructions: u64) -> bool {
        let Some(slot) = self.steps.get_mut(self.len) else {
            return false;
        };
        *slot = (frame, instructions);
        self.len += 1;
        true
    }

    /// Median, 99th percentile and max.
    #[must_use]
    pub fn summary(&self) -> Summary {
        let steps = &self.steps[..self.len];
        let (mut max, mut max_frame, mut total) = (0, 0, 0);
        let mut sorted = [0u64; MAX_STEPS];
        for (slot, &(frame, count)) in sorted.iter_mut().zip(steps) {
            *slot = count;
            total += count;
            if count > max {
                (max, max_frame) = (count, frame);
            }
        }
        let sorted = &mut sorted[..self.len];
        sorted.sort_unstable();
        Summary {
            steps: self.len,
            median: self.len.checked_sub(1).map_or(0, |last| sorted[last / 2]),
            p99: (self.len * 99)
                .div_ceil(100)
                .checked_sub(1)
                .map_or(0, |i| sorted[i]),
            max,
            max_frame,
            total,
        }
    }
}

impl Default for StepCounts {
    fn default() -> Self {
        Self::new()
    }
}
