//! # ecam-mc: the motion-controller (Repeat-type) face
//!
//! (Being written.)
