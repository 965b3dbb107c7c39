//! CIGI 3.3 weather from a host, for precip.
//!
//! Image generators in flight, driving and ship simulators take their weather from
//! the host over CIGI (the Common Image Generator Interface, SISO). This crate reads
//! the host's UDP messages — IG Control (the header: version, byte order from its
//! magic number, frame counter) and Weather Control for the global scope — and turns
//! them into a precip [`Weather`](precip_model::Weather) ([`HostWeather`]; the
//! mapping of severity to intensity is documented there). Written from the CIGI 3.3
//! ICD's layouts ([`packet`]). Short, unknown, oversized or malformed datagrams are
//! counted and skipped ([`CigiReceiver`], [`PacketCounts`]), never a panic.
//!
//! The viewer listens with `--cigi PORT` (headless and in the window). Not yet here
//! (issue 16): the other weather layers' looks (fog, clouds), hail, regional and
//! entity scopes, and the IG's answers (Start of Frame) to the host.

pub mod error;
pub mod host_weather;
pub mod packet;
pub mod receiver;

pub use error::CigiError;
pub use host_weather::{Applied, HostWeather};
pub use packet::{ByteOrder, IgControl, Packet, WeatherControl, parse_message};
pub use receiver::{CigiReceiver, PacketCounts};
