//! A segment of CSP drives driven by `ethercrab`: bring-up to OP with
//! distributed clocks (SYNC0 = the cycle time), then one process-data
//! exchange per cycle.

use std::sync::{Arc, Mutex};
use std::thread::{self, JoinHandle};
use std::time::{Duration, Instant};

use ethercrab::subdevice_group::{DcConfiguration, HasDc, Op};
use ethercrab::{
    DcSync, DefaultLock, MainDevice, MainDeviceConfig, PduStorage, RetryBehaviour, SubDeviceGroup,
    SubDeviceState, Timeouts,
};
use futures_lite::future::block_on;

use crate::drive::Cia402Drive;
use crate::emulation::EmulatedSegment;
use crate::error::EthercatError;
use crate::link::InProcessLink;
use crate::pdo::{CspInputs, INPUTS_LEN, OUTPUTS_LEN};
use crate::rt::{RtConfig, configure_current_thread};

/// Most drives one segment carries.
pub const MAX_DRIVES: usize = 64;
/// Process image bytes for [`MAX_DRIVES`] CSP drives.
pub const MAX_PDI: usize = MAX_DRIVES * (OUTPUTS_LEN + INPUTS_LEN);
const MAX_FRAMES: usize = 16;
const MAX_PDU_DATA: usize = PduStorage::element_size(1100);

type Storage = PduStorage<MAX_FRAMES, MAX_PDU_DATA>;
type OpGroup = SubDeviceGroup<MAX_DRIVES, MAX_PDI, DefaultLock, Op, HasDc>;

/// Where the frames go.
#[derive(Clone, Debug)]
pub enum Transport {
    /// A network interface (raw socket; needs CAP_NET_RAW).
    Interface(String),
    /// An emulated segment in this process.
    Emulated(Arc<Mutex<EmulatedSegment>>),
}

/// Timing of a segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SegmentConfig {
    /// Process-data cycle, also the SYNC0 period.
    pub cycle: Duration,
    /// How long a frame may take to come back before the cycle counts it
    /// lost.
    pub frame_timeout: Duration,
    /// How long a state change (INIT → PRE-OP → SAFE-OP → OP) may take.
    pub state_timeout: Duration,
    /// Frames sent to settle the drives' clocks before SYNC0 starts.
    pub dc_static_sync_iterations: u32,
    /// `SCHED_FIFO` priority of the thread that sends and receives the
    /// frames (`None`: normal scheduling). With a real-time cycle it must
    /// be real-time too, or the cycle waits on a thread the scheduler may
    /// hold back.
    pub link_fifo_priority: Option<u8>,
}

impl Default for SegmentConfig {
    fn default() -> Self {
        Self {
            cycle: Duration::from_millis(1),
            frame_timeout: Duration::from_millis(30),
            state_timeout: Duration::from_secs(5),
            dc_static_sync_iterations: 1000,
            link_fifo_priority: None,
        }
    }
}

/// What one exchange found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CycleReport {
    /// Working counter of the process data (3 per drive: read + write,
    /// summed over the frames the image takes).
    pub working_counter: u16,
    /// The working counter the complete segment returned after bring-up.
    pub expected_working_counter: u16,
    /// Drives that did not answer.
    pub unreachable: usize,
    /// The frame did not come back at all.
    pub frame_lost: bool,
    /// DC system time of the reference drive, ns.
    pub dc_system_time: u64,
    /// Time to the next SYNC0-aligned cycle start, as ethercrab computes
    /// it from the DC time.
    pub next_cycle_wait: Duration,
}

impl CycleReport {
    /// The working counter was short (a drive or a cable is missing).
    pub fn working_counter_error(&self) -> bool {
        self.frame_lost || self.working_counter != self.expected_working_counter
    }
}

/// Kept only to live as long as the segment (dropping the emulated link
/// stops its thread).
enum Link {
    Emulated { _link: InProcessLink },
    Interface { _thread: JoinHandle<()> },
}

/// A segment in OP, ready to cycle.
pub struct Segment {
    maindevice: MainDevice<'static>,
    group: OpGroup,
    drives: Vec<Cia402Drive>,
    config: SegmentConfig,
    expected_working_counter: u16,
    _link: Link,
}

impl core::fmt::Debug for Segment {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Segment")
            .field("drives", &self.drives.len())
            .field("config", &self.config)
            .finish()
    }
}

impl Segment {
    /// Finds the drives, checks each maps the CSP process data, starts
    /// distributed clocks with SYNC0 at the cycle time and brings every
    /// drive to OP. Drives are left disabled (CiA 402 "switch on
    /// disabled"); [`Cia402Drive::set_request`] enables them.
    pub fn bring_up(transport: Transport, config: SegmentConfig) -> Result<Self, EthercatError> {
        if config.cycle.is_zero() || config.cycle > Duration::from_secs(1) {
            return Err(EthercatError::CycleTime(config.cycle));
        }
        // Each segment owns its frame storage for the life of the process
        // (ethercrab's storage must outlive every frame in flight).
        let storage: &'static Storage = Box::leak(Box::new(PduStorage::new()));
        let (tx, rx, pdu_loop) = storage.try_split().map_err(|()| EthercatError::Storage)?;
        let link_rt = RtConfig {
            period: config.cycle,
            fifo_priority: config.link_fifo_priority,
            cpu: None,
        };
        let link = match transport {
            Transport::Emulated(segment) => Link::Emulated {
                _link: InProcessLink::spawn(tx, rx, segment, link_rt)?,
            },
            Transport::Interface(name) => {
                let task = ethercrab::std::tx_rx_task(&name, tx, rx).map_err(|source| {
                    EthercatError::Interface {
                        name: name.clone(),
                        source,
                    }
                })?;
                Link::Interface {
                    _thread: thread::Builder::new()
                        .name("ecam-ethercat-tx-rx".into())
                        .spawn(move || {
                            // Refusal falls back to normal scheduling; the
                            // cycle thread reports what it got.
                            let _ = configure_current_thread(&link_rt);
                            let _ = block_on(task);
                        })?,
                }
            }
        };
        let maindevice = MainDevice::new(
            pdu_loop,
            Timeouts {
                pdu: config.frame_timeout,
                state_transition: config.state_timeout,
                // EEPROM reads happen at bring-up only; a loaded host must
                // not fail them (ethercrab's default is 10 ms).
                eeprom: config.state_timeout,
                ..Timeouts::default()
            },
            MainDeviceConfig {
                dc_static_sync_iterations: config.dc_static_sync_iterations,
                retry_behaviour: RetryBehaviour::Count(2),
            },
        );
        let group = block_on(bring_up_group(&maindevice, config))?;
        let drives = vec![Cia402Drive::new(); group.len()];
        // 3 per drive (read and write of its process data); more when
        // ethercrab splits the image over frames and a drive's outputs
        // straddle two of them. The first exchange with every drive in OP
        // tells.
        let minimum = u16::try_from(drives.len() * 3).unwrap_or(u16::MAX);
        let mut segment = Self {
            maindevice,
            group,
            drives,
            config,
            expected_working_counter: minimum,
            _link: link,
        };
        // One exchange so every drive's state and position are known.
        let first = segment.exchange()?;
        if first.unreachable > 0 || first.working_counter < minimum {
            return Err(EthercatError::NotOp);
        }
        segment.expected_working_counter = first.working_counter;
        Ok(segment)
    }

    /// Number of drives.
    pub fn len(&self) -> usize {
        self.drives.len()
    }

    /// The segment has no drives (never true after a bring-up).
    pub fn is_empty(&self) -> bool {
        self.drives.is_empty()
    }

    /// The timing the segment was brought up with.
    pub fn config(&self) -> SegmentConfig {
        self.config
    }

    /// The drives, in line order.
    pub fn drives(&self) -> &[Cia402Drive] {
        &self.drives
    }

    /// The drives, to command them.
    pub fn drives_mut(&mut self) -> &mut [Cia402Drive] {
        &mut self.drives
    }

    /// Name a drive reports (its SII order string).
    pub fn drive_name(&self, position: usize) -> Option<String> {
        self.group
            .subdevice(&self.maindevice, position)
            .ok()
            .map(|sd| sd.name().to_string())
    }

    /// Packs the outputs, exchanges process data (with the DC time), and
    /// unpacks the inputs. A lost frame or a drive that does not answer
    /// is reported, not an error: the cycle must go on.
    pub fn exchange(&mut self) -> Result<CycleReport, EthercatError> {
        for (position, drive) in self.drives.iter_mut().enumerate() {
            let subdevice = self.group.subdevice(&self.maindevice, position)?;
            let mut io = subdevice.io_raw_mut();
            drive.outputs().pack(io.outputs())?;
        }
        let expected = self.expected_working_counter;
        let response = match block_on(self.group.tx_rx_dc(&self.maindevice)) {
            Ok(response) => response,
            Err(ethercrab::error::Error::Timeout(_)) => {
                for drive in &mut self.drives {
                    drive.update(None);
                }
                return Ok(CycleReport {
                    expected_working_counter: expected,
                    unreachable: self.drives.len(),
                    frame_lost: true,
                    next_cycle_wait: self.config.cycle,
                    ..CycleReport::default()
                });
            }
            Err(e) => return Err(e.into()),
        };
        let mut unreachable = 0;
        for (position, drive) in self.drives.iter_mut().enumerate() {
            let answered = matches!(
                response.subdevice_states.get(position),
                Some(SubDeviceState::Op | SubDeviceState::SafeOp)
            );
            if answered {
                let subdevice = self.group.subdevice(&self.maindevice, position)?;
                let io = subdevice.io_raw();
                drive.update(Some(CspInputs::unpack(io.inputs())?));
            } else {
                unreachable += 1;
                drive.update(None);
            }
        }
        Ok(CycleReport {
            working_counter: response.working_counter,
            expected_working_counter: expected,
            unreachable,
            frame_lost: false,
            dc_system_time: response.extra.dc_system_time,
            next_cycle_wait: response.extra.next_cycle_wait,
        })
    }
}

async fn bring_up_group(
    maindevice: &MainDevice<'static>,
    config: SegmentConfig,
) -> Result<OpGroup, EthercatError> {
    let mut group = maindevice
        .init_single_group::<MAX_DRIVES, MAX_PDI>(ethercrab::std::ethercat_now)
        .await?;
    if group.is_empty() {
        return Err(EthercatError::NoDrives);
    }
    for mut subdevice in group.iter_mut(maindevice) {
        subdevice.set_dc_sync(DcSync::Sync0);
    }
    let group = group.into_pre_op_pdi(maindevice).await?;
    for (position, subdevice) in group.iter(maindevice).enumerate() {
        let io = subdevice.io_raw();
        if io.inputs().len() != INPUTS_LEN || io.outputs().len() != OUTPUTS_LEN {
            return Err(EthercatError::NotCsp {
                position,
                name: subdevice.name().to_string(),
                inputs: io.inputs().len(),
                outputs: io.outputs().len(),
            });
        }
    }
    let group = group
        .configure_dc_sync(
            maindevice,
            DcConfiguration {
                // SYNC0 starts a few cycles after configuration, on a
                // whole multiple of the cycle (ethercrab rounds it).
                start_delay: config.cycle * 10,
                sync0_period: config.cycle,
                // Outputs are sent half a cycle before the drives latch
                // them, the usual margin for frame jitter.
                sync0_shift: config.cycle / 2,
            },
        )
        .await?;
    let group = group.into_safe_op(maindevice).await?;
    let group = group.request_into_op(maindevice).await?;
    let deadline = Instant::now() + config.state_timeout;
    loop {
        let response = group.tx_rx_dc(maindevice).await?;
        if response.all_op() {
            return Ok(group);
        }
        if Instant::now() > deadline {
            return Err(EthercatError::NotOp);
        }
        thread::sleep(config.cycle);
    }
}
