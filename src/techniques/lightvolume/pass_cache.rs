//! Recorded propagation passes kept from frame to frame: a pass's secondary
//! command buffer is replayed as long as what it reads is unchanged (its entries
//! region, and the light states in the slots those entries name).

use super::groups::PropagationGroup;
use crate::render::frame_params::GpuLight;
use crate::vk::commands::SecondaryCommands;

/// Everything a recorded pass depends on besides the fixed resources.
#[derive(Clone, Debug, PartialEq)]
pub struct PassKey {
    pub axis: usize,
    pub travel: i32,
    /// Per member: slot, signed factor, the state the slot must hold.
    pub entries: Vec<(u32, f32, GpuLight)>,
}

impl PassKey {
    pub fn new(group: &PropagationGroup, slots: &[u32]) -> PassKey {
        PassKey {
            axis: group.axis,
            travel: group.travel,
            entries: group.members.iter().zip(slots).map(|(m, &s)| (s, m.factor, m.state)).collect(),
        }
    }

    /// Whether the slot buffer (mirrored in `slot_states`) still holds what the
    /// pass reads.
    pub fn valid(&self, slot_states: &[Option<GpuLight>]) -> bool {
        self.entries.iter().all(|(slot, _, state)| slot_states.get(*slot as usize) == Some(&Some(*state)))
    }
}

pub struct RecordedPass {
    pub key: PassKey,
    pub name: String,
    pub first_entry: usize,
    pub commands: SecondaryCommands,
    /// Update counter when the pass last ran.
    pub last_used: u64,
}

impl RecordedPass {
    pub fn entry_count(&self) -> usize {
        self.key.entries.len()
    }
}

/// Passes kept at most; the least recently used beyond it are dropped.
const KEEP: usize = 64;

#[derive(Default)]
pub struct PassCache {
    pub passes: Vec<RecordedPass>,
}

impl PassCache {
    pub fn find(&self, key: &PassKey) -> Option<usize> {
        self.passes.iter().position(|p| &p.key == key)
    }

    /// Drops passes whose slots changed.
    pub fn retain_valid(&mut self, slot_states: &[Option<GpuLight>]) {
        self.passes.retain(|p| p.key.valid(slot_states));
    }

    /// Drops the least recently used passes beyond the cache size.
    pub fn trim(&mut self) {
        if self.passes.len() > KEEP {
            self.passes.sort_by_key(|p| std::cmp::Reverse(p.last_used));
            self.passes.truncate(KEEP);
        }
    }

    /// First free run of `len` entries below `capacity`, around the regions of
    /// the passes kept.
    pub fn free_region(&self, len: usize, capacity: usize) -> Option<usize> {
        let mut used: Vec<(usize, usize)> =
            self.passes.iter().map(|p| (p.first_entry, p.first_entry + p.entry_count())).collect();
        used.sort_unstable();
        let mut start = 0;
        for (a, b) in used {
            if a >= start + len {
                break;
            }
            start = start.max(b);
        }
        (start + len <= capacity).then_some(start)
    }
}
