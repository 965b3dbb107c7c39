//! What sensors see through the weather: [`optics`] (extinction, backscatter and
//! the meteorological optical range at 550, 905 and 1550 nm) and [`lidar`] (beams
//! against the particles and the scene). `docs/model.md` gives the equations.

pub mod lidar;
pub mod optics;
