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
//! The IG answers every frame with Start of Frame ([`StartOfFrame`],
//! [`CigiReceiver::send_start_of_frame`]) to the host it last heard from (or one
//! given with [`CigiReceiver::reply_to`]), in the host's byte order, echoing its
//! frame counter, so a host running synchronously can pace itself on it.
//!
//! The host flies the eyepoint ([`HostView`]): Entity Control places the ownship
//! (and other entities) by latitude, longitude, altitude and attitude on the
//! scene's local tangent plane ([`GeodeticOrigin`]), View Control hangs the view
//! drawn on an entity, View Definition sets its field of view, and Celestial Sphere
//! Control's date and time place the sun ([`HostView::sun`]);
//! [`CigiReceiver::take_eyepoint`] hands the camera over, and
//! [`CigiReceiver::wait_for_host_frame`] keeps the IG in lockstep with a host
//! running synchronously.
//!
//! The viewer listens with `--cigi PORT` (headless and in the window; `--origin`,
//! `--cigi-view`, `--cigi-lockstep`). Not yet here: hail, regional and entity
//! weather scopes, the other views of a multi-channel rig in one IG.

pub mod error;
pub mod host_view;
pub mod host_weather;
pub mod packet;
pub mod receiver;

pub use error::CigiError;
pub use host_view::{Eyepoint, GeodeticOrigin, HostView};
pub use host_weather::{Applied, HostWeather};
pub use packet::{
    ByteOrder, EntityControl, IgControl, Packet, StartOfFrame, ViewControl, ViewDefinition,
    WeatherControl, parse_message, parse_start_of_frame,
};
pub use receiver::{CigiReceiver, PacketCounts};
