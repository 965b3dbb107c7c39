//! The particles: their state on the GPU ([`particle`]), what each kind is and does
//! ([`kind`]: one table, every per-kind decision), where they are born
//! ([`emitter`], [`birth`]), how one moves in a sub-step ([`step`]), what they land
//! on ([`ground`]) and the counter-based random numbers every property is drawn
//! from ([`rng`]), all with WGSL twins of the same names (`shaders/`).
//! `docs/model.md` §1 gives the life cycle.

pub mod birth;
pub mod emitter;
pub mod ground;
pub mod kind;
pub mod particle;
pub mod rng;
pub mod step;
