//! Steps of the cost breakdown of one IPSVI frame (`sweeplab bench ipsvi
//! --breakdown`): the same line dispatches with the work of a full
//! frame switched on one part at a time, by a specialization constant of
//! glsl/ipsvi_line.comp. Study baselines, not illumination results.

/// What the line shader does, cumulatively. The write path (view samples) is
/// split in the order that keeps the data flow closest to the frame's: the
/// stores come on before what computes their values, so from `Stores` on the
/// texels' depths, and with them every march's length, are the frame's
/// (before it every front stays at the box entry and the reads march to it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum BreakdownStep {
    /// Ray casting of the block's pixels only: no cache read (unshadowed light),
    /// no cache write.
    Lines,
    /// Adds bilinear cache reads at every sample (no piecewise integration).
    CacheReads,
    /// Adds piecewise integration back to the cache front.
    Piecewise,
    /// Adds the invocations after the pixels: view samples carry the previous
    /// blocks' writes into the history pair; light rays advance their texels
    /// (all of light-rays' writes).
    Carry,
    /// Adds the two sample stores (value, depth and stamp) at every run end, racy,
    /// storing the light the writing sample read as it is.
    Stores,
    /// Adds the claim pass of `farthest`/`nearest` (the next block's medium march
    /// and its atomics); stores still racy.
    ClaimPass,
    /// Adds the claim check: only the claimed winner stores.
    ClaimCheck,
    /// Adds the writing sample's own one-step light segment composited in.
    OwnSegment,
    /// Adds the texel-ray march of `write_value = "texel-ray"`: the IPSVI frame.
    #[default]
    Full,
    /// Nothing: every invocation returns at once. The sync study's empty
    /// workload: the sweep's dispatches and synchronization with no work in
    /// flight to drain (not a breakdown step, so not in [`BreakdownStep::ALL`]).
    Empty,
}

impl BreakdownStep {
    pub const ALL: [BreakdownStep; 9] = [
        BreakdownStep::Lines,
        BreakdownStep::CacheReads,
        BreakdownStep::Piecewise,
        BreakdownStep::Carry,
        BreakdownStep::Stores,
        BreakdownStep::ClaimPass,
        BreakdownStep::ClaimCheck,
        BreakdownStep::OwnSegment,
        BreakdownStep::Full,
    ];

    pub fn name(self) -> &'static str {
        match self {
            BreakdownStep::Lines => "lines",
            BreakdownStep::CacheReads => "cache reads",
            BreakdownStep::Piecewise => "piecewise integration",
            BreakdownStep::Carry => "history carry",
            BreakdownStep::Stores => "sample stores",
            BreakdownStep::ClaimPass => "claim pass",
            BreakdownStep::ClaimCheck => "claim check",
            BreakdownStep::OwnSegment => "own segment",
            BreakdownStep::Full => "texel-ray march (full IPSVI)",
            BreakdownStep::Empty => "empty workload",
        }
    }

    /// The value of the shader's STEP constant (glsl/ipsvi_line.comp STEP_*).
    pub fn shader_step(self) -> u32 {
        match self {
            BreakdownStep::Lines => 0,
            BreakdownStep::CacheReads => 1,
            BreakdownStep::Piecewise => 2,
            BreakdownStep::Carry => 3,
            BreakdownStep::Stores => 4,
            BreakdownStep::ClaimPass => 5,
            BreakdownStep::ClaimCheck => 6,
            BreakdownStep::OwnSegment => 7,
            BreakdownStep::Full => 8,
            BreakdownStep::Empty => 9,
        }
    }

    /// Whether the step runs the invocations after the pixels (carry/advance).
    pub fn writes_history(self) -> bool {
        self.shader_step() >= BreakdownStep::Carry.shader_step() && self != BreakdownStep::Empty
    }

    /// Whether the step runs the claim pass of `farthest`/`nearest`.
    pub fn claims(self) -> bool {
        self.shader_step() >= BreakdownStep::ClaimPass.shader_step() && self != BreakdownStep::Empty
    }
}
