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
//! `--cigi-view`, `--cigi-lockstep`). Not yet here: regional and entity
//! weather scopes, the other views of a multi-channel rig in one IG.
//!
//! # Example
//!
//! A host's Weather Control for moderate hail over the whole area becomes a
//! precip weather:
//!
//! ```
//! use precip_cigi::packet::WeatherControl;
//! use precip_cigi::{Applied, HostWeather};
//! use precip_model::{PrecipitationKind, Weather};
//!
//! let hail = WeatherControl {
//!     entity_region_id: 0,
//!     layer: 7, // hail
//!     humidity_percent: 80,
//!     enabled: true,
//!     random_winds: false,
//!     cloud_type: 0,
//!     scope: 0, // global
//!     severity: 3,
//!     air_temperature_c: 18.0,
//!     visibility_m: 0.0,
//!     coverage_percent: 100.0,
//!     base_elevation_m: 0.0,
//!     thickness_m: 0.0,
//!     transition_band_m: 0.0,
//!     horizontal_wind_mps: 12.0,
//!     vertical_wind_mps: 0.0,
//!     wind_from_deg: 250.0,
//! };
//! let mut host = HostWeather::new(Weather::default());
//! let Applied::Changed(weather) = host.apply(&hail) else {
//!     panic!("a global hail layer changes the weather");
//! };
//! assert_eq!(weather.kind, PrecipitationKind::Hail);
//! assert!((weather.intensity_mm_per_h - 10.0).abs() < 1e-6); // severity 3
//! // Stones are few: hail alone hardly hides the distance (a storm's rain does).
//! assert!(weather.visibility_m() > 10_000.0);
//! ```

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
