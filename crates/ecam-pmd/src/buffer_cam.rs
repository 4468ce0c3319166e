//! A cam table read straight from buffer memory.
//!
//! Document 002's tables are N signed values evenly spaced over `CamCounts`
//! master counts (N − 1 linear pieces, fractional spacing allowed). The
//! running cam reads the buffer on every evaluation, so `WriteBuffer` into a
//! running cam's table takes effect at once: the document allows changing
//! table data during execution "at their own risk", and this is the
//! behaviour a user watching the device would see. Moving or resizing the
//! buffer of an active cam is refused instead (it would change N and so the
//! spacing under the running cam).

use std::cell::RefCell;
use std::rc::Rc;

use ecam_core::{CamCurve, Cursor, Kinematics};

use crate::{BufferId, BufferMemory};

/// Memory shared between the processor (which writes it) and running cams.
pub type SharedMemory = Rc<RefCell<BufferMemory>>;

/// An evenly spaced cam table living in buffer `buffer` of shared memory.
#[derive(Clone, Debug)]
pub struct BufferCam {
    memory: SharedMemory,
    buffer: BufferId,
    cam_counts: i64,
    /// Number of table values, fixed when the cam starts.
    values: u32,
}

impl BufferCam {
    /// A view of `values` entries of `buffer` spread over `cam_counts` counts.
    /// The caller checks `values >= 2` and `cam_counts >= 2`.
    pub fn new(memory: SharedMemory, buffer: BufferId, cam_counts: i64, values: u32) -> Self {
        Self {
            memory,
            buffer,
            cam_counts: cam_counts.max(1),
            values: values.max(2),
        }
    }

    fn value(&self, index: u32) -> i64 {
        self.memory
            .try_borrow()
            .map_or(0, |m| i64::from(m.read(self.buffer, index)))
    }

    /// Master counts per table piece (may be fractional).
    fn spacing(&self) -> f64 {
        self.cam_counts as f64 / f64::from(self.values - 1)
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
        self.value(self.values - 1)
    }
    fn segment_count(&self) -> usize {
        (self.values - 1) as usize
    }

    fn eval(&self, master: f64, cursor: &mut Cursor) -> Kinematics {
        let pieces = self.values - 1;
        let x = (master.clamp(0.0, self.cam_counts as f64) / self.spacing()).max(0.0);
        // `x` is within [0, pieces]; the float→int cast saturates.
        let i = (x.floor() as u32).min(pieces - 1);
        cursor.segment = i as usize;
        let (y0, y1) = (self.value(i) as f64, self.value(i + 1) as f64);
        let u = x - f64::from(i);
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
    fn sees_new_buffer_values() {
        let c = cam(&[0, 100, 200], 100);
        c.memory.borrow_mut().set_write_index(c.buffer, 1).unwrap();
        c.memory.borrow_mut().write(c.buffer, 50).unwrap();
        assert_eq!(c.position(50.0, &mut Cursor::new()), 50.0);
    }
}
