//! The shape of a line-sweep frame (IPSVI): how wide its line dispatches are
//! and how long the longest serial chain of work in them is. It does not
//! depend on the device: it shows on lavapipe, where frame times cannot, that
//! a frame of narrow dispatches with long chains leaves a large GPU idle and
//! waiting on latency (the H200 keeps about 270,000 invocations in flight).

use serde::Serialize;

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LineShape {
    /// The line kernel, as `render` prints it (`serial`, `segmented x32`).
    pub kernel: String,
    /// Line dispatches that shade pixels (a sweep's claim-only dispatch excluded).
    pub line_dispatches: u32,
    /// Invocations dispatched per line dispatch (workgroups times their size),
    /// median and largest over the frame's line dispatches.
    pub invocations_median: u32,
    pub invocations_max: u32,
    /// The longest serial chain any invocation of a line dispatch ran (view
    /// samples marched, in every pass, plus the steps of every march toward
    /// the light), counted on the device; median and largest over the line
    /// dispatches.
    pub chain_median: u32,
    pub chain_max: u32,
    /// The same chain for each role of a line's invocations alone, median
    /// over the line dispatches: which part of a line it waits for.
    pub chain_median_by_role: ChainsByRole,
    /// Per role, the line dispatches whose longest chain is that role's (a
    /// tie counts for each role in it; a dispatch with no chain for none): a
    /// role whose median is short can still bind the long lines.
    pub lines_bound_by: ChainsByRole,
    /// Tests only: order-free digests of every claim and of where every view
    /// ray stopped (glsl/ipsvi_line_interface.glsl `DIGESTS`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub claim_digest: Option<u64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stop_digest: Option<u64>,
    /// The segmented kernel's view-stops pass (one dispatch a frame, before
    /// the sweeps; none where rays never stop or the kernel is serial).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stops_pass: Option<StopsPassShape>,
}

/// A frame's view-stops pass: its invocations and the longest serial chain
/// of samples any of them marched (the opacity of its segment, and of the
/// segment holding the stop once more).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct StopsPassShape {
    pub invocations: u64,
    pub chain: u32,
}

/// What a line's invocations do, each with its own longest chain: march a
/// pixel's view ray (or a segment of it), carry or write a cache texel, or
/// march a pixel of the next block to claim its texels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct ChainsByRole {
    pub pixels: u32,
    pub texels: u32,
    pub claims: u32,
}

impl ChainsByRole {
    pub fn longest(&self) -> u32 {
        self.pixels.max(self.texels).max(self.claims)
    }
}

impl LineShape {
    /// From each line dispatch's (invocations, longest chain of each role).
    pub fn from_dispatches(kernel: String, dispatches: &[(u32, ChainsByRole)]) -> LineShape {
        let median_max = |mut v: Vec<u32>| -> (u32, u32) {
            v.sort_unstable();
            (v.get(v.len() / 2).copied().unwrap_or(0), v.last().copied().unwrap_or(0))
        };
        let (invocations_median, invocations_max) = median_max(dispatches.iter().map(|d| d.0).collect());
        let (chain_median, chain_max) = median_max(dispatches.iter().map(|d| d.1.longest()).collect());
        let role_median =
            |role: fn(&ChainsByRole) -> u32| median_max(dispatches.iter().map(|d| role(&d.1)).collect()).0;
        let bound_by = |role: fn(&ChainsByRole) -> u32| {
            dispatches.iter().filter(|d| d.1.longest() > 0 && role(&d.1) == d.1.longest()).count() as u32
        };
        LineShape {
            kernel,
            line_dispatches: dispatches.len() as u32,
            invocations_median,
            invocations_max,
            chain_median,
            chain_max,
            chain_median_by_role: ChainsByRole {
                pixels: role_median(|c| c.pixels),
                texels: role_median(|c| c.texels),
                claims: role_median(|c| c.claims),
            },
            lines_bound_by: ChainsByRole {
                pixels: bound_by(|c| c.pixels),
                texels: bound_by(|c| c.texels),
                claims: bound_by(|c| c.claims),
            },
            claim_digest: None,
            stop_digest: None,
            stops_pass: None,
        }
    }

    /// One line for `render`, `compare` and the viewer's log.
    pub fn summary(&self) -> String {
        let stops = self.stops_pass.map_or(String::new(), |p| {
            format!("; view-stops pass: {} invocations, longest chain {}", p.invocations, p.chain)
        });
        format!(
            "line shape ({}): {} line dispatches, invocations per dispatch median {} max {}, longest serial \
             chain per invocation median {} max {} (medians of pixels {}, texels {}, claims {}; the longest in \
             {}, {} and {} lines){stops}",
            self.kernel,
            self.line_dispatches,
            self.invocations_median,
            self.invocations_max,
            self.chain_median,
            self.chain_max,
            self.chain_median_by_role.pixels,
            self.chain_median_by_role.texels,
            self.chain_median_by_role.claims,
            self.lines_bound_by.pixels,
            self.lines_bound_by.texels,
            self.lines_bound_by.claims
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians_and_maxima_over_dispatches() {
        let roles = |pixels, texels, claims| ChainsByRole { pixels, texels, claims };
        let dispatches = [(64, roles(10, 2, 4)), (512, roles(30, 2, 300)), (128, roles(20, 3, 1))];
        let s = LineShape::from_dispatches("serial".into(), &dispatches);
        assert_eq!((s.line_dispatches, s.invocations_median, s.invocations_max), (3, 128, 512));
        // Each dispatch's chain is its longest role's: 10, 300, 20.
        assert_eq!((s.chain_median, s.chain_max), (20, 300));
        assert_eq!(s.chain_median_by_role, roles(20, 2, 4));
        assert!(s.summary().contains("median 128 max 512"), "{}", s.summary());
        // The pixels are the longest in two lines, the claims in one.
        assert_eq!(s.lines_bound_by, roles(2, 0, 1));
        assert!(
            s.summary().contains("(medians of pixels 20, texels 2, claims 4; the longest in 2, 0 and 1 lines)"),
            "{}",
            s.summary()
        );
        assert!(!s.summary().contains("view-stops"), "{}", s.summary());
        let stops = LineShape { stops_pass: Some(StopsPassShape { invocations: 4096, chain: 17 }), ..s };
        assert!(
            stops.summary().ends_with("; view-stops pass: 4096 invocations, longest chain 17"),
            "{}",
            stops.summary()
        );
        let none = LineShape::from_dispatches("serial".into(), &[]);
        assert_eq!((none.line_dispatches, none.chain_max), (0, 0));
    }

    #[test]
    fn a_tie_binds_each_role_in_it_and_an_empty_line_none() {
        let roles = |pixels, texels, claims| ChainsByRole { pixels, texels, claims };
        let dispatches = [(64, roles(5, 5, 1)), (64, roles(0, 0, 0)), (64, roles(1, 7, 7)), (64, roles(2, 1, 0))];
        let s = LineShape::from_dispatches("segmented x32".into(), &dispatches);
        assert_eq!(s.lines_bound_by, roles(2, 2, 1));
    }
}
