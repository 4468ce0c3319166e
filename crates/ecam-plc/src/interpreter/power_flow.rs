//! The power flow of a rung, the FX way: each LD starts a logic block, AND
//! and OR join a contact to the top block, ANB/ORB join the last two blocks,
//! and MPS/MRD/MPP keep branch points. The top block is the power flow that
//! coils and applied instructions see.

use crate::il::Join;

/// The stack of logic blocks and the stack of MPS branch points.
#[derive(Clone, Debug, Default)]
pub(super) struct PowerFlow {
    blocks: Vec<bool>,
    pushed: Vec<bool>,
}

impl PowerFlow {
    /// The power flow: the top logic block (off when there is none).
    pub(super) fn power(&self) -> bool {
        self.blocks.last().copied().unwrap_or(false)
    }

    /// Forgets every block and branch point (start of a scan, a jump).
    pub(super) fn clear(&mut self) {
        self.blocks.clear();
        self.pushed.clear();
    }

    /// Joins a contact's value: LD starts a block (a new rung when it
    /// follows an output and no branch point is open), AND puts it in
    /// series with the top block, OR in parallel.
    pub(super) fn join(&mut self, join: Join, value: bool, after_output: bool) {
        match join {
            Join::Load => {
                if after_output && self.pushed.is_empty() {
                    self.blocks.clear();
                }
                self.blocks.push(value);
            }
            Join::And => {
                if let Some(top) = self.blocks.last_mut() {
                    *top = *top && value;
                }
            }
            Join::Or => {
                if let Some(top) = self.blocks.last_mut() {
                    *top = *top || value;
                }
            }
        }
    }

    /// ANB (`series`) or ORB: the last two blocks become one.
    pub(super) fn join_blocks(&mut self, series: bool) {
        let last = self.blocks.pop().unwrap_or(false);
        if let Some(top) = self.blocks.last_mut() {
            *top = if series { *top && last } else { *top || last };
        }
    }

    /// MPS: keeps the power flow as a branch point.
    pub(super) fn push(&mut self) {
        let power = self.power();
        self.pushed.push(power);
    }

    /// MRD (`keep`) or MPP: the top block takes the branch point's power
    /// flow; MPP also drops the branch point.
    pub(super) fn restore(&mut self, keep: bool) {
        let saved = if keep {
            self.pushed.last().copied()
        } else {
            self.pushed.pop()
        };
        if let (Some(saved), Some(top)) = (saved, self.blocks.last_mut()) {
            *top = saved;
        }
    }
}
