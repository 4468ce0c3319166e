//! `ecam serve`'s piece that stays in the binary: the designer page's files,
//! compiled in ([`assets`]). The listeners are [`ecam_serve::net`]'s, the
//! fieldbus cycle of `--ethercat` is [`ecam_serve::ethercat`]'s.

pub mod assets;
