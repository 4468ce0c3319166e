//! # ecam-engine: the cam runtime
//!
//! (Being written.) One `tick()` per control cycle.
#![no_std]
