//! The five operands of `DECAM S1 S2 S3 D1 D2`, checked once at load.

use ecam_core::CODE_PARAMETER;

use super::offsets;
use crate::device::{C_COUNT, D_COUNT, Device};
use crate::operation_error::OperationError;

/// S1: where the master position comes from (document 003, "Master axis setting").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MasterOperand {
    /// Counter `Cn` (high-speed counters C200+ are 32-bit, C0–C199 16-bit).
    Counter(u16),
    /// 32-bit value in `Dn`, `Dn+1`.
    Register(u16),
    /// Virtual time base `Kn`: one master count every n × 100 µs.
    TimeBase(u32),
}

/// Checked operands of one DECAM instruction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DecamOperands {
    /// S1, the master.
    pub master: MasterOperand,
    /// S2, first word of the register block (`D` number).
    pub block: u16,
    /// S3, the external start signal (X or M).
    pub start: Device,
    /// D1, pulse output Y0–Y3 (0–3).
    pub pulse_output: u8,
    /// D2, direction output (a Y).
    pub direction: Device,
}

fn parameter(message: String) -> OperationError {
    OperationError::new(CODE_PARAMETER, message)
}

impl DecamOperands {
    /// Checks the operands the way the manual restricts them.
    ///
    /// # Errors
    /// Code 6781 when S1 is not a counter, a D register pair or K ≥ 1; when the
    /// 40-word block at S2 does not fit D0–D8511; when S3 is not an X or M;
    /// when D1 is not Y0–Y3; when D2 is not a Y.
    pub fn new(
        master: MasterOperand,
        block: u16,
        start: Device,
        pulse_output: u8,
        direction: Device,
    ) -> Result<Self, OperationError> {
        match master {
            MasterOperand::Counter(n) if n >= C_COUNT => {
                return Err(parameter(format!(
                    "DECAM master C{n} does not exist (C0-C255)"
                )));
            }
            MasterOperand::Register(n) if n.checked_add(1).is_none_or(|hi| hi >= D_COUNT) => {
                return Err(parameter(format!(
                    "DECAM master D{n} needs D{n} and the next word"
                )));
            }
            MasterOperand::TimeBase(0) => {
                return Err(parameter(
                    "DECAM time base K0: the master needs K1 (100 us per count) or more".into(),
                ));
            }
            _ => {}
        }
        if u32::from(block) + offsets::block_words(0) > u32::from(D_COUNT) {
            return Err(parameter(format!(
                "DECAM block D{block} does not fit: it needs D{block}..D{block}+39 and the table after it"
            )));
        }
        if !matches!(start, Device::X(_) | Device::M(_)) || start.check().is_err() {
            return Err(parameter(format!(
                "DECAM start signal {start} must be an X or M device"
            )));
        }
        if pulse_output > 3 {
            return Err(parameter(format!(
                "DECAM pulse output Y{pulse_output:o} must be Y0-Y3"
            )));
        }
        if !matches!(direction, Device::Y(_)) || direction.check().is_err() {
            return Err(parameter(format!(
                "DECAM direction output {direction} must be a Y output"
            )));
        }
        // One terminal cannot carry both the pulse train and a direction level:
        // the level written each tick would garble the pulses D8140… count.
        if direction == Device::Y(u16::from(pulse_output)) {
            return Err(parameter(format!(
                "DECAM direction output {direction} is the pulse output D1 itself: use another Y"
            )));
        }
        Ok(Self {
            master,
            block,
            start,
            pulse_output,
            direction,
        })
    }

    /// The D number of `S2 + offset` (the block's fit was checked for offsets below 40).
    pub(crate) fn reg(&self, offset: u16) -> u16 {
        self.block.saturating_add(offset)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepts_the_manual_instruction() {
        let ops = DecamOperands::new(
            MasterOperand::Counter(231),
            2000,
            Device::X(0),
            0,
            Device::Y(1),
        );
        assert!(ops.is_ok());
    }

    #[test]
    fn rejects_bad_operands_with_6781() {
        let bad = [
            DecamOperands::new(MasterOperand::TimeBase(0), 0, Device::X(0), 0, Device::Y(1)),
            DecamOperands::new(
                MasterOperand::Register(8511),
                0,
                Device::X(0),
                0,
                Device::Y(1),
            ),
            DecamOperands::new(
                MasterOperand::Counter(231),
                8480,
                Device::X(0),
                0,
                Device::Y(1),
            ),
            DecamOperands::new(
                MasterOperand::Counter(231),
                0,
                Device::Y(0),
                0,
                Device::Y(1),
            ),
            DecamOperands::new(
                MasterOperand::Counter(231),
                0,
                Device::X(0),
                4,
                Device::Y(1),
            ),
            DecamOperands::new(
                MasterOperand::Counter(231),
                0,
                Device::X(0),
                0,
                Device::M(1),
            ),
            DecamOperands::new(
                MasterOperand::Counter(231),
                0,
                Device::X(0),
                2,
                Device::Y(2),
            ),
        ];
        for result in bad {
            assert_eq!(result.map_err(|e| e.code), Err(6781));
        }
    }
}
