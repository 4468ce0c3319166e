//! # ecam-pmd: the motion-processor face
//!
//! Emulates the electronic-cam profile mode of a motion processor as
//! document 002 describes it: cam tables of evenly spaced signed 32-bit
//! values in buffer memory, `SetCam`/`GetCam` with `CamBufferID`,
//! `CamCounts`, `CamStartCount`, `CamSource` and the read-only offsets,
//! the `StartCam` breakpoint/event action, abrupt and smooth stops, and the
//! status words. The cam itself runs on `ecam-engine` (repeat coupling,
//! bumpless start). Time is simulated: one [`MotionProcessor::tick`] per
//! processor cycle.
//!
//! Use [`MotionProcessor`] from Rust, or [`ScriptRunner`] to run the
//! document's command scripts (what `ecam pmd run` does). Not for real
//! hardware: there is no servo loop, and actual positions follow commanded
//! ones exactly.
//!
//! ```
//! use ecam_pmd::{CamParam, MotionProcessor};
//!
//! // Document 002: three values [0, 100, 200] over CamCounts 100, started
//! // at input 0; as the input goes from 100 to 101 the output goes 200 → 202.
//! let mut p = MotionProcessor::default();
//! p.set_buffer_length(1, 3)?;
//! for v in [0, 100, 200] {
//!     p.write_buffer(1, v)?;
//! }
//! p.set_profile_mode(0, 8)?;
//! p.update(0)?;
//! p.set_cam(0, CamParam::CamBufferId, 1)?;
//! p.set_cam(0, CamParam::CamCounts, 100)?;
//! p.set_cam(0, CamParam::CamSource, 0x0001)?; // actual position of axis 1
//! p.set_event_action(0, 0, 9)?; // immediate event, StartCam
//! p.move_to(1, 100, 100)?;
//! p.run(100);
//! assert_eq!(p.commanded_position(0)?, 200);
//! p.move_to(1, 101, 1)?;
//! p.tick();
//! assert_eq!(p.commanded_position(0)?, 202);
//! # Ok::<(), ecam_pmd::PmdError>(())
//! ```

mod axis;
pub mod breakpoint;
mod buffer;
mod buffer_cam;
mod cam_param;
mod error;
#[doc(hidden)]
pub mod fuzz;
mod processor;
mod runner;
mod running_cam;
pub mod script;

pub use axis::{ProfileMode, StopMode, activity_bit, event_bit};
pub use buffer::{BUFFER_COUNT, BufferId, BufferMemory, BufferWindow, MEMORY_DWORDS};
pub use buffer_cam::{BufferCam, SharedMemory};
pub use cam_param::{CamParam, CamSettings, CamSource, MAX_CAM_COUNTS, SourceRegister};
pub use error::PmdError;
pub use processor::{MAX_AXES, MotionProcessor};
pub use runner::{Report, ScriptRunner};
pub use running_cam::{CamCycle, RunningCam};

use breakpoint::Breakpoint;
