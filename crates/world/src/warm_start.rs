//! Warm starting across steps: each block starts from the impulses of the previous step's block
//! of the same body pair anchored nearest to it (within [`MATCH_RADIUS`]).
//!
//! Contacts are rebuilt every step, so blocks are matched by where they act, not by index.

use std::collections::HashMap;
use std::ops::Range;

use nalgebra::Point3;
use tatami_contact::{Contact, ContactModel, ContactProjection};
use tatami_lcp::Problem;

/// Largest distance (m) between a block's anchor and its previous one for the impulses to carry
/// over: resting contacts move far less per step; a sliding contact that moved further starts
/// from zero, as without warm starting.
pub const MATCH_RADIUS: f64 = 0.02;

/// One solved block of the previous step.
#[derive(Debug, Clone)]
struct Entry {
    anchor: Point3<f64>,
    impulses: Range<usize>,
}

/// Impulses of the previous step's blocks, by body pair.
#[derive(Debug, Clone, Default)]
pub(crate) struct WarmStartCache {
    blocks: HashMap<(usize, usize), Vec<Entry>>,
    impulses: Vec<f64>,
    anchors: Vec<Point3<f64>>,
}

impl WarmStartCache {
    /// Remembers the solved impulses of every block of `problem`.
    pub(crate) fn store(
        &mut self,
        model: ContactModel,
        contacts: &[Contact],
        contact_blocks: &[Range<usize>],
        problem: &Problem<ContactProjection>,
    ) {
        self.blocks.values_mut().for_each(Vec::clear);
        self.impulses.clear();
        for (contact, blocks) in contacts.iter().zip(contact_blocks) {
            model.anchors(contact, &mut self.anchors);
            let entries = self
                .blocks
                .entry((contact.body_a.0, contact.body_b.0))
                .or_default();
            for (block, anchor) in problem.blocks[blocks.clone()].iter().zip(&self.anchors) {
                let start = self.impulses.len();
                self.impulses
                    .extend(problem.rows[block.rows.clone()].iter().map(|r| r.impulse));
                entries.push(Entry {
                    anchor: *anchor,
                    impulses: start..self.impulses.len(),
                });
            }
        }
    }

    /// Writes the matched previous impulses into the rows of `problem`'s blocks.
    pub(crate) fn load(
        &mut self,
        model: ContactModel,
        contacts: &[Contact],
        contact_blocks: &[Range<usize>],
        problem: &mut Problem<ContactProjection>,
    ) {
        for (contact, blocks) in contacts.iter().zip(contact_blocks) {
            let Some(entries) = self.blocks.get(&(contact.body_a.0, contact.body_b.0)) else {
                continue;
            };
            model.anchors(contact, &mut self.anchors);
            for (block, anchor) in problem.blocks[blocks.clone()].iter().zip(&self.anchors) {
                let nearest = entries
                    .iter()
                    .filter(|e| e.impulses.len() == block.rows.len())
                    .map(|e| ((e.anchor - anchor).norm(), e))
                    .min_by(|a, b| a.0.total_cmp(&b.0));
                if let Some((distance, entry)) = nearest
                    && distance <= MATCH_RADIUS
                {
                    for (row, &impulse) in problem.rows[block.rows.clone()]
                        .iter_mut()
                        .zip(&self.impulses[entry.impulses.clone()])
                    {
                        row.impulse = impulse;
                    }
                }
            }
        }
    }
}
