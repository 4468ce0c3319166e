//! A cam table taken from buffer memory.
//!
//! Document 002's tables are N signed values evenly spaced over `CamCounts`
//! master counts (N − 1 linear pieces, fractional spacing allowed). A
//! running cam works on a copy of the buffer taken when it starts; values
//! written into the buffer while it runs (the document allows changing table
//! data during execution "at their own risk") take over at the next seam
//! the input crosses, where the engine continues the output from the
//! slave position at the seam. Changing the values under the running cam at
//! once would step the output (the accumulated stroke was fixed from the
//! old first and last values), and a step is what a servo trips on. Moving
//! or resizing the buffer of an active cam is refused (it would change N and
//! so the spacing under the running cam).

use std::cell::RefCell;
use std::rc::Rc;

use ecam_core::{CamCurve, Cursor, Kinematics};

use crate::{BufferId, BufferMemory};

/// Memory shared between the processor (which writes it) and running cams.
pub type SharedMemory = Rc<RefCell<BufferMemory>>;

/// An evenly spaced cam table copied from buffer `buffer` of shared memory.
#[derive(Clone, Debug)]
pub struct BufferCam {
    memory: SharedMemory,
    buffer: BufferId,
    cam_counts: i64,
    /// The table values (at least two), as the buffer held them.
    values: Vec<i64>,
    /// The memory's revision when the values were copied.
    revision: u64,
}

impl BufferCam {
    /// A copy of `values` entries of `buffer` spread over `cam_counts`
    /// counts. The caller checks `values >= 2` and `cam_counts >= 2`.
    pub fn new(memory: SharedMemory, buffer: BufferId, cam_counts: i64, values: u32) -> Self {
        let (values, revision) = match memory.try_borrow() {
            Ok(m) => (
                (0..values.max(2))
                    .map(|i| i64::from(m.read(buffer, i)))
                    .collect(),
                m.revision(),
            ),
            Err(_) => (vec![0; values.max(2) as usize], 0),
        };
        Self {
            memory,
            buffer,
            cam_counts: cam_counts.max(1),
            values,
            revision,
        }
    }

    /// A fresh copy when the buffer was written since this one was taken
    /// and holds other values; `None` otherwise.
    pub fn refreshed(&self) -> Option<Self> {
        let revision = self.memory.try_borrow().ok()?.revision();
        if revision == self.revision {
            return None;
        }
        let fresh = Self::new(
            self.memory.clone(),
            self.buffer,
            self.cam_counts,
            u32::try_from(self.values.len()).unwrap_or(u32::MAX),
        );
        Some(fresh)
    }

    /// True when both hold the same table.
    pub fn same_table(&self, other: &Self) -> bool {
        self.values == other.values && self.cam_counts == other.cam_counts
    }

    fn value(&self, index: usize) -> i64 {
        self.values.get(index).copied().unwrap_or(0)
    }

    fn pieces(&self) -> usize {
        self.values.len().saturating_sub(1).max(1)
    }

    /// Master counts per table piece (may be fractional).
    fn spacing(&self) -> f64 {
        self.cam_counts as f64 / self.pieces() as f64
    }
}

impl CamCurve for BufferCam {
    fn master_first(&self) -> i64 {
        0
    }
    fn master_last(&self) -> i64 {
        self.cam_counts
    }
    fn slave_first(&self) -> i64 {
        self.value(0)
    }
    fn slave_last(&self) -> i64 {
        self.value(self.values.len().saturating_sub(1))
    }
    fn segment_count(&self) -> usize {
        self.pieces()
    }

    fn eval(&self, master: f64, cursor: &mut Cursor) -> Kinematics {
        let pieces = self.pieces();
        let x = (master.clamp(0.0, self.cam_counts as f64) / self.spacing()).max(0.0);
        // `x` is within [0, pieces]; the float→int cast saturates.
        let i = (x.floor() as usize).min(pieces - 1);
        cursor.segment = i;
        let (y0, y1) = (self.value(i) as f64, self.value(i + 1) as f64);
        let u = x - i as f64;
        Kinematics {
            s: y0 + (y1 - y0) * u,
            v: (y1 - y0) / self.spacing(),
            a: 0.0,
            j: 0.0,
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn cam(values: &[i64], counts: i64) -> BufferCam {
        let mut m = BufferMemory::new();
        let id = BufferId::new(1).unwrap();
        m.set_length(id, values.len() as i64).unwrap();
        for &v in values {
            m.write(id, v).unwrap();
        }
        BufferCam::new(Rc::new(RefCell::new(m)), id, counts, values.len() as u32)
    }

    #[test]
    fn three_values_over_100_counts() {
        let c = cam(&[0, 100, 200], 100);
        let mut cur = Cursor::new();
        assert_eq!(c.position(50.0, &mut cur), 100.0);
        assert_eq!(c.position(100.0, &mut cur), 200.0);
        assert_eq!(c.position(25.0, &mut cur), 50.0);
        assert_eq!(c.stroke(), 200);
        assert_eq!(c.eval(1.0, &mut cur).v, 2.0);
    }

    #[test]
    fn fractional_spacing() {
        // 4 values over 10 counts: pieces of 10/3 counts.
        let c = cam(&[0, 30, 60, 90], 10);
        let mut cur = Cursor::new();
        assert!((c.position(5.0, &mut cur) - 45.0).abs() < 1e-9);
        assert_eq!(c.position(10.0, &mut cur), 90.0);
    }

    #[test]
    fn keeps_its_copy_and_offers_a_fresh_one_after_a_write() {
        let c = cam(&[0, 100, 200], 100);
        assert!(c.refreshed().is_none());
        c.memory.borrow_mut().set_write_index(c.buffer, 1).unwrap();
        c.memory.borrow_mut().write(c.buffer, 50).unwrap();
        assert_eq!(c.position(50.0, &mut Cursor::new()), 100.0, "its own copy");
        let fresh = c.refreshed().unwrap();
        assert_eq!(fresh.position(50.0, &mut Cursor::new()), 50.0);
        assert!(!fresh.same_table(&c));
        assert!(fresh.refreshed().is_none());
    }
}
