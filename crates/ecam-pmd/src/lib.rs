//! # ecam-pmd: the motion-processor face
//!
//! (Being written.)
