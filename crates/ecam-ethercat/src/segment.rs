//! A segment of CSP drives driven by `ethercrab`: bring-up to OP with
//! distributed clocks (SYNC0 = the cycle time), then one process-data
//! exchange per cycle on the caller's thread, a reply deadline of the
//! cycle's own, and the acyclic steps the recovery of a drive needs.

use std::time::{Duration, Instant};

use ethercrab::subdevice_group::{DcConfiguration, HasDc, Op};
use ethercrab::{
    DcSync, DefaultLock, EtherCrabWireRead, MainDevice, MainDeviceConfig, PduStorage,
    RetryBehaviour, SubDeviceGroup, SubDeviceState, Timeouts,
};

use crate::coe::Emergency;
use crate::drive::Cia402Drive;
use crate::error::EthercatError;
pub use crate::link::Transport;
use crate::link::{self, Link, LinkStats, LoopId};
use crate::pdo::{INPUTS_LEN, OUTPUTS_LEN, PdoLayout};
use crate::poll_sleep::async_io_free_sleep;
use crate::startup::{self, Configured, DriveSetup, StartupError};

/// Most drives one segment carries.
pub const MAX_DRIVES: usize = 64;
/// Process image bytes for [`MAX_DRIVES`] CSP drives.
pub const MAX_PDI: usize = MAX_DRIVES * (OUTPUTS_LEN + INPUTS_LEN);
const MAX_FRAMES: usize = 16;
const MAX_PDU_DATA: usize = PduStorage::element_size(1100);
/// Longest a bring-up may take as a whole, whatever ethercrab's own
/// timeouts say (a bring-up never hangs).
const BRING_UP_LIMIT: Duration = Duration::from_secs(60);

type Storage = PduStorage<MAX_FRAMES, MAX_PDU_DATA>;
type OpGroup = SubDeviceGroup<MAX_DRIVES, MAX_PDI, DefaultLock, Op, HasDc>;

/// Timing of a segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SegmentConfig {
    /// Process-data cycle, also the SYNC0 period.
    pub cycle: Duration,
    /// How long a cycle waits for its reply; a reply later than this is
    /// counted lost and discarded when it comes.
    pub reply_timeout: Duration,
    /// How long a frame of the bring-up or of a recovery step may take to
    /// come back (ethercrab retries it twice).
    pub frame_timeout: Duration,
    /// How long a state change (INIT → PRE-OP → SAFE-OP → OP) may take.
    pub state_timeout: Duration,
    /// Frames sent to settle the drives' clocks before SYNC0 starts.
    pub dc_static_sync_iterations: u32,
    /// How long before the drives' SYNC0 edge the process data frame is
    /// meant to leave the master.
    pub sync0_shift: Duration,
}

impl SegmentConfig {
    /// Defaults for a cycle: the reply may take up to 80 % of it, the
    /// frame leaves half a cycle before SYNC0.
    pub fn for_cycle(cycle: Duration) -> Self {
        Self {
            cycle,
            reply_timeout: cycle * 4 / 5,
            frame_timeout: Duration::from_millis(30),
            state_timeout: Duration::from_secs(5),
            dc_static_sync_iterations: 1000,
            sync0_shift: cycle / 2,
        }
    }
}

impl Default for SegmentConfig {
    fn default() -> Self {
        Self::for_cycle(Duration::from_millis(1))
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
    /// Drives that did not answer, or answered from a state other than OP.
    pub unreachable: usize,
    /// The reply did not come back by the deadline (lost, or late: a late
    /// reply is discarded when it comes).
    pub frame_lost: bool,
    /// DC system time of the reference drive when the frame passed it,
    /// ns (0 when the frame was lost).
    pub dc_system_time: u64,
}

impl CycleReport {
    /// The working counter was short (a drive or a cable is missing) or
    /// nothing came back.
    pub fn working_counter_error(&self) -> bool {
        self.frame_lost || self.working_counter != self.expected_working_counter
    }
}

/// EtherCAT state of a drive as the last exchange read it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AlState {
    /// Not read (no answer).
    #[default]
    Unknown,
    /// INIT.
    Init,
    /// PRE-OP.
    PreOp,
    /// BOOT.
    Boot,
    /// SAFE-OP (inputs valid, outputs ignored).
    SafeOp,
    /// OP.
    Op,
}

impl AlState {
    fn from_ethercrab(state: SubDeviceState) -> Self {
        match state {
            SubDeviceState::Init => Self::Init,
            SubDeviceState::PreOp => Self::PreOp,
            SubDeviceState::Bootstrap => Self::Boot,
            SubDeviceState::SafeOp => Self::SafeOp,
            SubDeviceState::Op => Self::Op,
            _ => Self::Unknown,
        }
    }

    /// From the state bits of the AL status register (0x0130).
    pub fn from_register(value: u16) -> Self {
        match value & 0x0F {
            1 => Self::Init,
            2 => Self::PreOp,
            3 => Self::Boot,
            4 => Self::SafeOp,
            8 => Self::Op,
            _ => Self::Unknown,
        }
    }

    /// The name in status lines and JSON.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Unknown => "none",
            Self::Init => "INIT",
            Self::PreOp => "PRE-OP",
            Self::Boot => "BOOT",
            Self::SafeOp => "SAFE-OP",
            Self::Op => "OP",
        }
    }
}

/// The AL status code (register 0x0134) in words, ETG1000.6 table 11.
pub fn al_status_text(code: u16) -> String {
    match ethercrab::AlStatusCode::unpack_from_slice(&code.to_le_bytes()) {
        Ok(known) => known.to_string(),
        Err(_) => format!("AL status code {code:#06x}"),
    }
}

/// What the master learnt of a drive at bring-up.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DriveInfo {
    /// The name the drive reports (its SII order string).
    pub name: String,
    /// Vendor id, product code, revision and serial number (SII).
    pub identity: [u32; 4],
    /// It kept its own PDO mapping (ecam decodes it as read back).
    pub fixed_mapping: bool,
    /// 0x1C32/0x1C33 were set to DC SYNC0 (false: it has none).
    pub sync_parameters: bool,
}

impl core::fmt::Display for DriveInfo {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let [vendor, product, revision, serial] = self.identity;
        write!(
            f,
            "{} (vendor {vendor:#010x}, product {product:#010x}, revision {revision:#x}, serial {serial})",
            self.name
        )?;
        if self.fixed_mapping {
            f.write_str(", its own PDO order")?;
        }
        if !self.sync_parameters {
            f.write_str(", no 0x1C32/0x1C33")?;
        }
        Ok(())
    }
}

/// A single-register step of a drive's recovery, run between cycles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AcyclicStep {
    /// Read AL status (0x0130) and AL status code (0x0134).
    ReadAlStatus,
    /// Write AL control (0x0120): the requested state, with the error
    /// acknowledge bit.
    RequestState(u8),
    /// Read the message waiting in the drive's mailbox (SM1), if any: an
    /// emergency is how a drive tells its error in detail.
    ReadMailbox,
}

/// The answer of an [`AcyclicStep`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AcyclicAnswer {
    /// AL status: state, error flag, status code.
    AlStatus {
        /// The state.
        state: AlState,
        /// The error flag (bit 4).
        error: bool,
        /// The AL status code.
        code: u16,
    },
    /// The write was taken.
    Written,
    /// The mailbox held nothing.
    MailboxEmpty,
    /// The mailbox held a message that is not an emergency.
    MailboxOther,
    /// The mailbox held an emergency.
    Emergency(Emergency),
}

/// A segment in OP, ready to cycle.
pub struct Segment {
    link: Link,
    /// Bring-up, recovery steps: ethercrab's timeouts and retries.
    acyclic: MainDevice<'static>,
    /// Process data: no timeout or retry of ethercrab's (the cycle's
    /// deadline decides).
    cyclic: MainDevice<'static>,
    group: OpGroup,
    drives: Vec<Cia402Drive>,
    info: Vec<DriveInfo>,
    /// Where each drive's CSP objects sit in its process data.
    layouts: Vec<PdoLayout>,
    /// The configuration's `[[drive]]` entries.
    setups: Vec<DriveSetup>,
    al_states: Vec<AlState>,
    config: SegmentConfig,
    expected_working_counter: u16,
}

impl core::fmt::Debug for Segment {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Segment")
            .field("drives", &self.drives.len())
            .field("config", &self.config)
            .field("link", &self.link)
            .finish()
    }
}

fn storage() -> Result<
    (
        ethercrab::PduTx<'static>,
        ethercrab::PduRx<'static>,
        ethercrab::PduLoop<'static>,
    ),
    EthercatError,
> {
    // ethercrab's storage must outlive every frame in flight: each
    // segment keeps its two for the life of the process.
    let storage: &'static Storage = Box::leak(Box::new(PduStorage::new()));
    storage.try_split().map_err(|()| EthercatError::Storage)
}

impl Segment {
    /// [`Segment::bring_up_with`] without `[[drive]]` entries: every
    /// drive gets ecam's CoE configuration, none is checked against an
    /// identity.
    pub fn bring_up(transport: Transport, config: SegmentConfig) -> Result<Self, EthercatError> {
        Self::bring_up_with(transport, config, Vec::new())
    }

    /// Finds the drives, configures each in PRE-OP over CoE (identity
    /// checked against `setups`, CSP mode checked through 0x6061, the PDO
    /// mapping written and read back, 0x1C32/0x1C33 on SYNC0, the
    /// start-up SDOs: [`crate::startup`]), starts distributed clocks with
    /// SYNC0 at the cycle time and brings every drive to OP. Drives are
    /// left disabled (CiA 402 "switch on disabled");
    /// [`Cia402Drive::set_request`] enables them.
    pub fn bring_up_with(
        transport: Transport,
        config: SegmentConfig,
        setups: Vec<DriveSetup>,
    ) -> Result<Self, EthercatError> {
        if config.cycle.is_zero() || config.cycle > Duration::from_secs(1) {
            return Err(EthercatError::CycleTime(config.cycle));
        }
        let (acyclic_tx, acyclic_rx, acyclic_loop) = storage()?;
        let (cyclic_tx, cyclic_rx, cyclic_loop) = storage()?;
        let name = match &transport {
            Transport::Interface(name) => name.clone(),
            Transport::Emulated(_) => String::new(),
        };
        let mut link = Link::open(transport, (acyclic_tx, acyclic_rx), (cyclic_tx, cyclic_rx))
            .map_err(|source| EthercatError::Interface { name, source })?;
        let acyclic = MainDevice::new(
            acyclic_loop,
            Timeouts {
                pdu: config.frame_timeout,
                state_transition: config.state_timeout,
                // EEPROM reads happen at bring-up only; a loaded host must
                // not fail them (ethercrab's default is 10 ms).
                eeprom: config.state_timeout,
                // Mailbox waits likewise (ethercrab's 100 ms for the
                // request mailbox to empty fails on a stalled host).
                mailbox_echo: config.state_timeout,
                mailbox_response: config.state_timeout,
                ..Timeouts::default()
            },
            MainDeviceConfig {
                dc_static_sync_iterations: config.dc_static_sync_iterations,
                retry_behaviour: RetryBehaviour::Count(2),
            },
        );
        let cyclic = MainDevice::new(
            cyclic_loop,
            Timeouts {
                // Never: a timer of ethercrab's would live in async-io's
                // reactor thread; the cycle keeps its own deadline.
                pdu: Duration::MAX,
                ..Timeouts::default()
            },
            MainDeviceConfig {
                dc_static_sync_iterations: 0,
                retry_behaviour: RetryBehaviour::None,
            },
        );
        let deadline = Instant::now() + BRING_UP_LIMIT;
        let (group, configured) = guarded_run(
            &mut link,
            || bring_up_group(&acyclic, config, &setups),
            deadline,
        )?;
        let info = group
            .iter(&acyclic)
            .zip(&configured)
            .map(|(sd, c)| {
                let id = sd.identity();
                DriveInfo {
                    name: sd.name().to_string(),
                    identity: [id.vendor_id, id.product_id, id.revision, id.serial],
                    fixed_mapping: c.fixed_mapping,
                    sync_parameters: c.sync_parameters,
                }
            })
            .collect::<Vec<_>>();
        let layouts = configured.iter().map(|c| c.layout).collect();
        let drives = vec![Cia402Drive::new(); group.len()];
        // 3 per drive (read and write of its process data); more when
        // ethercrab splits the image over frames and a drive's outputs
        // straddle two of them. The first exchange with every drive in OP
        // tells.
        let minimum = u16::try_from(drives.len() * 3).unwrap_or(u16::MAX);
        let mut segment = Self {
            link,
            acyclic,
            cyclic,
            al_states: vec![AlState::Op; drives.len()],
            group,
            drives,
            info,
            layouts,
            setups,
            config,
            expected_working_counter: minimum,
        };
        // One exchange so every drive's state and position are known (a
        // loaded host gets a few tries).
        for _ in 0..10 {
            let first = segment.exchange()?;
            if !first.frame_lost {
                if first.unreachable > 0 || first.working_counter < minimum {
                    return Err(EthercatError::NotOp);
                }
                segment.expected_working_counter = first.working_counter;
                return Ok(segment);
            }
        }
        Err(EthercatError::NotOp)
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
        self.info.get(position).map(|i| i.name.clone())
    }

    /// What bring-up learnt of each drive.
    pub fn drive_info(&self) -> &[DriveInfo] {
        &self.info
    }

    /// The EtherCAT state of each drive as the last answered exchange read
    /// it.
    pub fn al_states(&self) -> &[AlState] {
        &self.al_states
    }

    /// Counts of the link (frames sent, late replies discarded, …).
    pub fn link_stats(&self) -> LinkStats {
        self.link.stats()
    }

    /// Packs the outputs, exchanges process data (with the DC time), and
    /// unpacks the inputs. A reply that is not back by the reply timeout
    /// is reported as a lost frame (the drives keep their last inputs),
    /// not an error: the cycle goes on with the next frame.
    pub fn exchange(&mut self) -> Result<CycleReport, EthercatError> {
        for (position, drive) in self.drives.iter_mut().enumerate() {
            let subdevice = self.group.subdevice(&self.cyclic, position)?;
            let mut io = subdevice.io_raw_mut();
            let layout = self.layouts.get(position).unwrap_or(&PdoLayout::CSP);
            layout.pack(&drive.outputs(), io.outputs())?;
        }
        let expected = self.expected_working_counter;
        let deadline = Instant::now() + self.config.reply_timeout;
        let response = match link::run(&mut self.link, self.group.tx_rx_dc(&self.cyclic), deadline)
        {
            Some(Ok(response)) => response,
            // No reply by the deadline, or ethercrab has no free frame
            // (every one still waiting): this cycle is lost.
            None | Some(Err(ethercrab::error::Error::Pdu(_))) => {
                self.link.forget(LoopId::Cyclic);
                for drive in &mut self.drives {
                    drive.update(None);
                }
                return Ok(CycleReport {
                    expected_working_counter: expected,
                    unreachable: self.drives.len(),
                    frame_lost: true,
                    ..CycleReport::default()
                });
            }
            Some(Err(e)) => return Err(e.into()),
        };
        let mut unreachable = 0;
        for (position, drive) in self.drives.iter_mut().enumerate() {
            let state = response
                .subdevice_states
                .get(position)
                .map_or(AlState::Unknown, |&s| AlState::from_ethercrab(s));
            if let Some(slot) = self.al_states.get_mut(position) {
                *slot = state;
            }
            // SAFE-OP drives send valid inputs (and ignore outputs).
            if matches!(state, AlState::Op | AlState::SafeOp) {
                let subdevice = self.group.subdevice(&self.cyclic, position)?;
                let io = subdevice.io_raw();
                let layout = self.layouts.get(position).unwrap_or(&PdoLayout::CSP);
                drive.update(Some(layout.unpack(io.inputs())?));
            } else {
                drive.update(None);
            }
            if state != AlState::Op {
                unreachable += 1;
            }
        }
        Ok(CycleReport {
            working_counter: response.working_counter,
            expected_working_counter: expected,
            unreachable,
            frame_lost: false,
            dc_system_time: response.extra.dc_system_time,
        })
    }

    /// Runs one recovery step for drive `position` on the acyclic loop,
    /// waiting at most `budget`. `None` when it did not complete (try
    /// again next cycle: every step may be repeated).
    pub fn acyclic_step(
        &mut self,
        position: usize,
        step: AcyclicStep,
        budget: Duration,
    ) -> Option<AcyclicAnswer> {
        let deadline = Instant::now() + budget;
        let subdevice = self.group.subdevice(&self.acyclic, position).ok()?;
        let answer = match step {
            AcyclicStep::ReadAlStatus => {
                let read = async {
                    let status = subdevice.register_read::<u16>(0x0130u16).await?;
                    let code = subdevice.register_read::<u16>(0x0134u16).await?;
                    Ok::<_, ethercrab::error::Error>((status, code))
                };
                let (status, code) = link::run(&mut self.link, read, deadline)?.ok()?;
                AcyclicAnswer::AlStatus {
                    state: AlState::from_register(status),
                    error: status & 0x10 != 0,
                    code,
                }
            }
            AcyclicStep::RequestState(state) => {
                let value = u16::from(state & 0x0F) | 0x10;
                link::run(
                    &mut self.link,
                    subdevice.register_write::<u16>(0x0120u16, value),
                    deadline,
                )?
                .ok()?;
                AcyclicAnswer::Written
            }
            AcyclicStep::ReadMailbox => {
                let acyclic = &self.acyclic;
                let read = async {
                    // SM1's registers: start, length, control, status.
                    let sm = subdevice.register_read::<[u8; 8]>(0x0808u16).await?;
                    let start = u16::from_le_bytes([sm[0], sm[1]]);
                    let len = u16::from_le_bytes([sm[2], sm[3]]);
                    if sm[5] & 0x08 == 0 || len == 0 {
                        return Ok(AcyclicAnswer::MailboxEmpty);
                    }
                    // Reading up to its last byte empties the mailbox.
                    let message = ethercrab::Command::fprd(subdevice.configured_address(), start)
                        .receive_slice(acyclic, len)
                        .await?;
                    Ok::<_, ethercrab::error::Error>(
                        Emergency::from_mailbox(&message)
                            .map_or(AcyclicAnswer::MailboxOther, AcyclicAnswer::Emergency),
                    )
                };
                link::run(&mut self.link, read, deadline)?.ok()?
            }
        };
        self.link.forget(LoopId::Acyclic);
        Some(answer)
    }

    /// Brings the whole segment up again (INIT → OP, distributed clocks
    /// afresh), for drives that lost their configuration (restarted,
    /// power-cycled). The drives' positions are read again; every drive is
    /// left disabled. Blocks for the bring-up (the line is stopped).
    ///
    /// # Errors
    /// As [`Segment::bring_up`]; the old group stays in place.
    pub fn reinitialise(&mut self) -> Result<(), EthercatError> {
        let deadline = Instant::now() + BRING_UP_LIMIT;
        let (acyclic, config, setups) = (&self.acyclic, self.config, &self.setups);
        let (group, configured) = guarded_run(
            &mut self.link,
            || bring_up_group(acyclic, config, setups),
            deadline,
        )?;
        if group.len() != self.drives.len() {
            return Err(EthercatError::DriveCount {
                expected: self.drives.len(),
                found: group.len(),
            });
        }
        self.group = group;
        self.layouts = configured.iter().map(|c| c.layout).collect();
        self.link.forget(LoopId::Acyclic);
        for drive in &mut self.drives {
            *drive = Cia402Drive::new();
        }
        for _ in 0..10 {
            if !self.exchange()?.frame_lost {
                return Ok(());
            }
        }
        Err(EthercatError::NotOp)
    }
}

/// Stack of the thread a bring-up runs on: ethercrab's futures for a
/// group of [`MAX_DRIVES`] are large, and a debug build copies them.
const BRING_UP_STACK: usize = 16 << 20;

/// Runs a bring-up on the link, on a thread of its own with a large
/// stack (the caller waits). ethercrab stops with a panic when an
/// emergency arrives in the middle of one of its SDO transfers; that ends
/// the bring-up with an error instead of the process.
fn guarded_run<T, F>(
    link: &mut Link,
    future: impl FnOnce() -> F + Send,
    deadline: Instant,
) -> Result<T, EthercatError>
where
    T: Send,
    F: std::future::Future<Output = Result<T, EthercatError>>,
{
    std::thread::scope(|scope| {
        let run = std::thread::Builder::new()
            .name("ecam-ethercat-bring-up".into())
            .stack_size(BRING_UP_STACK)
            .spawn_scoped(scope, move || {
                let future = Box::pin(future());
                link::run(link, future, deadline)
            })?;
        match run.join() {
            Ok(Some(result)) => result,
            Ok(None) => Err(EthercatError::NotOp),
            Err(_) => Err(EthercatError::MailboxInterrupted),
        }
    })
}

async fn bring_up_group(
    maindevice: &MainDevice<'static>,
    config: SegmentConfig,
    setups: &[DriveSetup],
) -> Result<(OpGroup, Vec<Configured>), EthercatError> {
    let mut group = maindevice
        .init_single_group::<MAX_DRIVES, MAX_PDI>(ethercrab::std::ethercat_now)
        .await?;
    if group.is_empty() {
        return Err(EthercatError::NoDrives);
    }
    if let Some(beyond) = setups.iter().find(|s| s.position >= group.len()) {
        return Err(EthercatError::Startup {
            position: beyond.position,
            name: String::new(),
            error: StartupError::NotOnSegment,
        });
    }
    for mut subdevice in group.iter_mut(maindevice) {
        subdevice.set_dc_sync(DcSync::Sync0);
    }
    let mut configured = Vec::with_capacity(group.len());
    for (position, subdevice) in group.iter(maindevice).enumerate() {
        let setup = setups.iter().find(|s| s.position == position);
        // On the heap: ethercrab's SDO futures are large, a thread's
        // stack is not.
        let done = Box::pin(startup::configure(&subdevice, setup, config.cycle))
            .await
            .map_err(|error| EthercatError::Startup {
                position,
                name: subdevice.name().to_string(),
                error,
            })?;
        configured.push(done);
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
    let shift = config.sync0_shift.min(config.cycle);
    let group = group
        .configure_dc_sync(
            maindevice,
            DcConfiguration {
                // SYNC0 starts a few cycles after configuration, on a
                // whole multiple of the cycle (ethercrab rounds it).
                start_delay: config.cycle * 10,
                sync0_period: config.cycle,
                // ethercrab's shift is counted from the SYNC0 edge to the
                // frame; ours from the frame to the next edge.
                sync0_shift: config.cycle - shift,
            },
        )
        .await?;
    let group = group.into_safe_op(maindevice).await?;
    let group = group.request_into_op(maindevice).await?;
    let deadline = Instant::now() + config.state_timeout;
    loop {
        let response = group.tx_rx_dc(maindevice).await?;
        if response.all_op() {
            return Ok((group, configured));
        }
        if Instant::now() > deadline {
            return Err(EthercatError::NotOp);
        }
        async_io_free_sleep(config.cycle).await;
    }
}
