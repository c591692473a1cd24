//! Per-step instruction counts and their summary (median, 99th percentile and max) for one
//! kind of step. The counts live in static buffers ([`StepCounts::take`]), not on the stack:
//! the stack high-water mark is then the book's own.

/// Most steps one [`StepCounts`] records.
pub const MAX_STEPS: usize = 1024;

/// Instruction counts of the steps of one kind (active or resting), in step order:
/// $12 \cdot$ [`MAX_STEPS`] bytes in `.bss`.
pub struct StepCounts {
    /// Frame of each recorded step.
    frames: [u32; MAX_STEPS],
    /// Instructions of each recorded step.
    instructions: [u64; MAX_STEPS],
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

/// The two static buffers of a run: active steps, then resting steps.
pub type Buffers = (&'static mut StepCounts, &'static mut StepCounts);

impl StepCounts {
    /// No steps yet.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            frames: [0; MAX_STEPS],
            instructions: [0; MAX_STEPS],
            len: 0,
        }
    }

    /// The run's two buffers, in `.bss`; `None` when they were taken already (they can be
    /// taken once).
    #[must_use]
    pub fn take() -> Option<Buffers> {
        let active = cortex_m::singleton!(: StepCounts = StepCounts::new())?;
        let resting = cortex_m::singleton!(: StepCounts = StepCounts::new())?;
        Some((active, resting))
    }

    /// Records the step of `frame` and its instructions; `false` (nothing recorded) when
    /// [`MAX_STEPS`] are already recorded.
    pub fn push(&mut self, frame: u32, instructions: u64) -> bool {
        if self.len == MAX_STEPS {
            return false;
        }
        self.frames[self.len] = frame;
        self.instructions[self.len] = instructions;
        self.len += 1;
        true
    }

    /// Median, 99th percentile and max; sorts the counts in place (the step order is lost,
    /// so it is called once, at the end).
    #[must_use]
    pub fn summary(&mut self) -> Summary {
        let (mut max, mut max_frame, mut total) = (0, 0, 0);
        for (&frame, &count) in self.frames[..self.len]
            .iter()
            .zip(&self.instructions[..self.len])
        {
            total += count;
            if count > max {
                (max, max_frame) = (count, frame);
            }
        }
        let sorted = &mut self.instructions[..self.len];
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
