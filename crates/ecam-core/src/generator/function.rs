//! A function of the master sampled evenly (the PC editor's "data
//! setting", document 003 §6.2): the parameters only. The expression is
//! evaluated by the front end (the command line's `exmex`), which samples
//! it with [`sample_function`](crate::table::sample_function).

use alloc::string::String;

/// Parameters of the function generator. The serde form uses the keys of
/// [`schema::FUNCTION`](super::schema::FUNCTION); what it leaves out keeps
/// the default.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Params {
    /// Slave position as a function of the master `x`; there is no default.
    pub expr: Option<String>,
    /// First master position.
    pub from: i64,
    /// Last master position.
    pub to: i64,
    /// Number of points, both ends included.
    pub points: usize,
}

impl Default for Params {
    /// No expression, master 0 to 36000 in 361 points (one every 100).
    fn default() -> Self {
        Self {
            expr: None,
            from: 0,
            to: 36_000,
            points: 361,
        }
    }
}
