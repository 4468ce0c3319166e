//! Where the synchronised zone sits ([`CamPlacement`]).

use crate::TableError;

/// Position of the synchronised zone in one cycle of the table.
///
/// Where the synchronised zone sits inside the generated table (ECAMTBX
/// K100/K101, parameter P6 high word, "cam curve").
///
/// The two copies of the manual disagree on rightCAM's number: the LX3VP copy
/// lists it as 5, the LX3VE copy as 4 (and has no 5). [`CamPlacement::from_code`]
/// accepts both; [`CamPlacement::code`] writes 5, the clean copy's value.
///
/// ```
/// use ecam_core::generator::CamPlacement;
///
/// assert_eq!(CamPlacement::from_code(4)?, CamPlacement::RightCam);
/// assert_eq!(CamPlacement::from_code(5)?, CamPlacement::RightCam);
/// assert_eq!(CamPlacement::RightCam.code(), 5);
/// # Ok::<(), ecam_core::TableError>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CamPlacement {
    /// Code 0: the table starts with the sync zone ("sync area on the left").
    #[default]
    LeftCam,
    /// Code 1: the sync zone is in the middle of the table; the table starts
    /// and ends halfway through the non-synchronised motion, and repeats.
    MidCamAll,
    /// Code 2: like [`CamPlacement::MidCamAll`] but starting from standstill:
    /// the table to run once before repeating `MidCamAll`.
    MidCamBegin,
    /// Code 3: like [`CamPlacement::MidCamAll`] but ending at standstill:
    /// the table to run once after `MidCamAll`; the cam stops when it completes.
    MidCamEnd,
    /// Code 5 (LX3VP copy) or 4 (LX3VE copy): the table ends with the sync zone.
    RightCam,
}

impl CamPlacement {
    /// All placements, in code order.
    pub const ALL: [CamPlacement; 5] = [
        Self::LeftCam,
        Self::MidCamAll,
        Self::MidCamBegin,
        Self::MidCamEnd,
        Self::RightCam,
    ];

    /// The placement for a P6 high-word code (both 4 and 5 mean rightCAM).
    ///
    /// # Errors
    /// [`TableError::Parameter`] (6781) for any other code.
    pub fn from_code(code: u16) -> Result<Self, TableError> {
        match code {
            0 => Ok(Self::LeftCam),
            1 => Ok(Self::MidCamAll),
            2 => Ok(Self::MidCamBegin),
            3 => Ok(Self::MidCamEnd),
            4 | 5 => Ok(Self::RightCam),
            _ => Err(TableError::Parameter {
                name: "cam curve (P6 high word)",
                reason: "must be 0 leftCAM, 1 midCAMall, 2 midCAMbegin, 3 midCAMend or 4/5 rightCAM",
            }),
        }
    }

    /// Every name and code [`CamPlacement::from_name`] accepts, for messages.
    pub const NAMES: &'static str =
        "left (0), mid-all (1), mid-begin (2), mid-end (3), right (5; 4 also accepted)";

    /// The placement's name in parameter files, flags and forms.
    pub const fn name(self) -> &'static str {
        match self {
            Self::LeftCam => "left",
            Self::MidCamAll => "mid-all",
            Self::MidCamBegin => "mid-begin",
            Self::MidCamEnd => "mid-end",
            Self::RightCam => "right",
        }
    }

    /// The placement for a name or a P6 high-word code written as text
    /// (`"4"` and `"5"` both mean rightCAM).
    pub fn from_name(text: &str) -> Option<Self> {
        match text {
            "0" | "left" => Some(Self::LeftCam),
            "1" | "mid-all" => Some(Self::MidCamAll),
            "2" | "mid-begin" => Some(Self::MidCamBegin),
            "3" | "mid-end" => Some(Self::MidCamEnd),
            "4" | "5" | "right" => Some(Self::RightCam),
            _ => None,
        }
    }

    /// The P6 high-word code (rightCAM as 5).
    pub const fn code(self) -> u16 {
        match self {
            Self::LeftCam => 0,
            Self::MidCamAll => 1,
            Self::MidCamBegin => 2,
            Self::MidCamEnd => 3,
            Self::RightCam => 5,
        }
    }
}

super::choice_serde::choice_serde!(CamPlacement, "placement");

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip() {
        for p in CamPlacement::ALL {
            assert_eq!(CamPlacement::from_code(p.code()), Ok(p));
            assert_eq!(CamPlacement::from_name(p.name()), Some(p));
        }
        assert_eq!(CamPlacement::from_name("4"), Some(CamPlacement::RightCam));
        assert_eq!(CamPlacement::from_code(4), Ok(CamPlacement::RightCam));
        assert_eq!(CamPlacement::from_code(6).unwrap_err().code(), 6781);
    }
}
