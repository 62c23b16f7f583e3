//! Steps of the cost breakdown of one IPSVI frame (`sweeplab bench ipsvi
//! --breakdown`): the same line dispatches with the work of a full
//! frame switched on one part at a time, by a specialization constant of
//! glsl/ipsvi_line.comp. Study baselines, not illumination results.

/// What the line shader does, cumulatively.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum BreakdownStep {
    /// Ray casting of the block's pixels only: no cache read (unshadowed light),
    /// no cache write.
    Lines,
    /// + bilinear cache reads at every sample (no piecewise integration).
    CacheReads,
    /// + piecewise integration back to the cache front.
    Piecewise,
    /// + cache writes (advance/carry, claims, sample stores): the IPSVI frame.
    #[default]
    Full,
}

impl BreakdownStep {
    pub const ALL: [BreakdownStep; 4] =
        [BreakdownStep::Lines, BreakdownStep::CacheReads, BreakdownStep::Piecewise, BreakdownStep::Full];

    pub fn name(self) -> &'static str {
        match self {
            BreakdownStep::Lines => "lines",
            BreakdownStep::CacheReads => "cache reads",
            BreakdownStep::Piecewise => "piecewise integration",
            BreakdownStep::Full => "cache writes (full IPSVI)",
        }
    }

    /// The value of the shader's STEP constant.
    pub fn shader_step(self) -> u32 {
        self as u32
    }
}
