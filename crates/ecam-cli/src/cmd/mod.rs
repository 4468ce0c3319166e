//! One module per subcommand.

pub mod ethercat;
pub mod install;
pub mod law;
pub mod mc;
pub mod plc;
pub mod pmd;
pub mod serve;
pub mod simulate;
pub mod table;
