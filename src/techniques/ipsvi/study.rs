//! What studies and tests set in code, never a scene file: baselines and cost
//! breakdown steps that are not illumination results, and the digests the
//! kernel tests compare. Kept out of [`super::IpsviSettings`], the
//! `[ipsvi]` table users set. `ipsvi.sync` stays there, `racy` included:
//! which synchronization separates the lines is what this project's users
//! study, in the viewer as in `bench sync`, and `racy` is the control they
//! hold a strategy against (validation reports its hazard). So does
//! `merge_sweeps`, a choice of how a frame is dispatched, not a measurement.

use super::breakdown::BreakdownStep;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IpsviStudy {
    /// Every sweep as one dispatch over all its lines (the same shader and
    /// pixels with no sweep to synchronize).
    pub single_dispatch_baseline: bool,
    /// Which parts of the line shader run (`bench ipsvi --breakdown`; `Empty`:
    /// the sync study's empty workload); `Full` is IPSVI.
    pub breakdown_step: BreakdownStep,
    /// Records the claim pass even where it cannot change the image (see
    /// [`super::IpsviSettings::records_claims`]): for the test that proves
    /// it cannot, and for studies whose configurations must all run it.
    pub keep_redundant_claims: bool,
    /// The line kernels sum a hash of every claim and of where every view
    /// ray stopped ([`crate::render::LineShape`]'s digests).
    pub digests: bool,
    /// Leaves out the barrier between the view-stops pass and the first line
    /// dispatch (tests only: synchronization validation must report it).
    pub omit_view_stops_barrier: bool,
}
