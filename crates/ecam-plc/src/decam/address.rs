//! Where a DECAM register block may start, as a user types it (`D2000`,
//! `2000`): the one check the designer page (through `ecam serve`) and
//! `ecam plc run --load` make, with messages naming the device's real kind.

use core::fmt;

use super::offsets::block_words;
use crate::device::{D_COUNT, Device, DeviceError};

/// Why a block cannot start there.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BlockAddressError {
    /// Not a device name, or a number past the device's range.
    Device {
        /// The text given.
        text: String,
        /// What is wrong with it.
        error: DeviceError,
    },
    /// A device of another kind (an auxiliary relay, an input…).
    Kind {
        /// The device named.
        device: Device,
    },
    /// A data register number past the last one (D8511).
    NoSuchRegister {
        /// The number given.
        number: u64,
    },
    /// A data register whose block runs past the last one.
    PastTheEnd {
        /// The block's first register.
        block: u16,
    },
}

impl fmt::Display for BlockAddressError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let last = D_COUNT - 1;
        match self {
            Self::Device { text, error } => write!(f, "`{text}`: {error}"),
            Self::Kind { device } => write!(
                f,
                "{device} is an {}, not a data register: a DECAM block starts at a D register, e.g. D2000",
                device.kind()
            ),
            Self::NoSuchRegister { number } => write!(
                f,
                "D{number} is past the last data register, D{last}: a DECAM block starts at D0 .. D{LAST_START}"
            ),
            Self::PastTheEnd { block } => write!(
                f,
                "a DECAM block at D{block} runs past D{last}: it needs {} registers from its first (its settings and a table of at least one point), so it starts at D{} at the latest",
                LEAST_WORDS, LAST_START
            ),
        }
    }
}

impl std::error::Error for BlockAddressError {}

/// Registers a block needs at least: offsets 0–39 and one point's words
/// ([`block_words`], the one home of the block's size; the live view
/// asks the same).
const LEAST_WORDS: u32 = block_words(1);
/// The last register a block may start at.
pub const LAST_START: u16 = D_COUNT - LEAST_WORDS as u16;

/// The first register of the DECAM block named by `text`: `D2000`, or
/// just `2000`.
///
/// ```
/// use ecam_plc::decam::{block_at, LAST_START};
///
/// assert_eq!(block_at("D2000"), Ok(2000));
/// assert_eq!(block_at(" 2000 "), Ok(2000));
/// assert!(block_at("M100").unwrap_err().to_string().contains("auxiliary relay"));
/// assert!(block_at("D9000").unwrap_err().to_string().contains("D8511"));
/// assert!(block_at(&format!("D{}", LAST_START + 1)).is_err());
/// ```
///
/// # Errors
/// A [`BlockAddressError`] naming the device and what is wrong.
pub fn block_at(text: &str) -> Result<u16, BlockAddressError> {
    let text = text.trim();
    let named = if text.bytes().all(|b| b.is_ascii_digit()) && !text.is_empty() {
        format!("D{text}")
    } else {
        text.to_string()
    };
    let number = named
        .strip_prefix(['D', 'd'])
        .filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
        .and_then(|n| n.parse::<u64>().ok());
    if let Some(number) = number.filter(|&n| n >= u64::from(D_COUNT)) {
        return Err(BlockAddressError::NoSuchRegister { number });
    }
    let device = Device::parse(&named).map_err(|error| BlockAddressError::Device {
        text: text.to_string(),
        error,
    })?;
    match device {
        Device::D(n) if n <= LAST_START => Ok(n),
        Device::D(n) => Err(BlockAddressError::PastTheEnd { block: n }),
        other => Err(BlockAddressError::Kind { device: other }),
    }
}
