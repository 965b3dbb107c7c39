//! CIGI messages of every kind precip reads, in both byte orders, fuzzed, and over
//! loopback UDP.

use std::net::UdpSocket;
use std::time::{Duration, Instant};

use precip_cigi::host_weather::{FOG_VISIBILITY_M, HAIL_MM_PER_H, RAIN_MM_PER_H, SNOW_MM_PER_H};
use precip_cigi::{
    Applied, ByteOrder, CigiError, CigiReceiver, HostWeather, Packet, StartOfFrame, WeatherControl,
    parse_message, parse_start_of_frame,
};
use precip_model::drawing::fog_layer::FogLayer;
use precip_model::{PrecipitationKind, Weather};
use proptest::prelude::*;

/// Writes packets as a host would, in `order`.
struct Writer {
    order: ByteOrder,
    bytes: Vec<u8>,
}

impl Writer {
    fn new(order: ByteOrder) -> Self {
        Self {
            order,
            bytes: Vec::new(),
        }
    }
    fn u16(&mut self, v: u16) {
        self.bytes.extend(match self.order {
            ByteOrder::Big => v.to_be_bytes(),
            ByteOrder::Little => v.to_le_bytes(),
        });
    }
    fn u32(&mut self, v: u32) {
        self.bytes.extend(match self.order {
            ByteOrder::Big => v.to_be_bytes(),
            ByteOrder::Little => v.to_le_bytes(),
        });
    }
    fn f32(&mut self, v: f32) {
        self.u32(v.to_bits());
    }
    fn f64(&mut self, v: f64) {
        self.bytes.extend(match self.order {
            ByteOrder::Big => v.to_bits().to_be_bytes(),
            ByteOrder::Little => v.to_bits().to_le_bytes(),
        });
    }
    /// Entity Control for an active entity: attitude (roll, pitch, yaw °), then
    /// latitude °, longitude °, altitude m.
    fn entity(&mut self, id: u16, attitude: [f32; 3], place: [f64; 3]) {
        self.bytes.extend([2, 48]);
        self.u16(id);
        self.bytes.extend([1, 0, 255, 0]);
        self.u16(0);
        self.u16(0);
        for v in attitude {
            self.f32(v);
        }
        for v in place {
            self.f64(v);
        }
    }
    /// View Control of view 0 on `entity`: every offset enabled.
    fn view_control(&mut self, entity: u16, offsets: [f32; 6]) {
        self.bytes.extend([16, 32]);
        self.u16(0);
        self.bytes.push(0);
        self.bytes.push(0b11_1111);
        self.u16(entity);
        for v in offsets {
            self.f32(v);
        }
    }
    /// View Definition of view 0: left, right, top, bottom half-angles.
    fn view_definition(&mut self, half_angles: [f32; 4]) {
        self.bytes.extend([21, 32]);
        self.u16(0);
        self.bytes.extend([0, 0b11_1100, 0, 0]);
        for v in [0.1, 10_000.0].into_iter().chain(half_angles) {
            self.f32(v);
        }
    }
    fn ig_control(&mut self, frame: u32) {
        self.bytes.extend([1, 24, 3, 0, (3 << 4) | 1, 0]);
        self.u16(0x8000);
        self.u32(frame);
        self.u32(0);
        self.u32(frame.saturating_sub(1));
        self.u32(0);
    }
    #[expect(clippy::too_many_arguments, reason = "one per field a test varies")]
    fn weather(
        &mut self,
        layer: u8,
        enabled: bool,
        severity: u8,
        temperature_c: f32,
        visibility_m: f32,
        coverage: f32,
        wind: (f32, f32, f32),
        scope: u8,
    ) {
        self.bytes.extend([12, 56]);
        self.u16(0);
        self.bytes
            .extend([layer, 40, u8::from(enabled), (severity << 2) | scope]);
        for v in [
            temperature_c,
            visibility_m,
            0.0,
            coverage,
            800.0,
            1_500.0,
            100.0,
            wind.0,
            wind.1,
            wind.2,
            1013.0,
            0.0,
        ] {
            self.f32(v);
        }
    }
}

/// The host frame counter of [`rain_message`].
const RAIN_HOST_FRAME: u32 = 42;

fn rain_message(order: ByteOrder, severity: u8) -> Vec<u8> {
    let mut w = Writer::new(order);
    w.ig_control(RAIN_HOST_FRAME);
    w.weather(4, true, severity, 12.0, 0.0, 100.0, (8.0, 0.0, 270.0), 0);
    w.bytes
}

#[test]
fn both_byte_orders_read_the_same_packets() {
    let big = parse_message(&rain_message(ByteOrder::Big, 3)).expect("big-endian");
    let little = parse_message(&rain_message(ByteOrder::Little, 3)).expect("little-endian");
    assert_eq!(big.len(), 2);
    let (Packet::IgControl(a), Packet::IgControl(b)) = (big[0], little[0]) else {
        panic!("IG Control first: {big:?}");
    };
    assert_eq!(
        (a.byte_order, b.byte_order),
        (ByteOrder::Big, ByteOrder::Little)
    );
    assert_eq!((a.host_frame, b.host_frame), (42, 42));
    assert_eq!((a.major_version, a.minor_version, a.ig_mode), (3, 3, 1));
    assert_eq!(big[1], little[1]);
    let Packet::WeatherControl(w) = big[1] else {
        panic!("weather second");
    };
    assert_eq!((w.layer, w.severity, w.scope, w.enabled), (4, 3, 0, true));
    assert!((w.air_temperature_c - 12.0).abs() < 1e-6 && (w.wind_from_deg - 270.0).abs() < 1e-6);
    assert!((w.base_elevation_m - 800.0).abs() < 1e-6 && (w.thickness_m - 1_500.0).abs() < 1e-6);
    assert!((w.transition_band_m - 100.0).abs() < 1e-6);
}

#[test]
fn every_precipitation_layer_sets_its_kind_and_severity_sets_the_rate() {
    let mut host = HostWeather::new(Weather::default());
    let cases = [
        (4u8, 12.0f32, PrecipitationKind::Rain),
        (5, -8.0, PrecipitationKind::DrySnow),
        (5, 0.0, PrecipitationKind::WetSnow),
        (6, 1.0, PrecipitationKind::Sleet),
        (8, 35.0, PrecipitationKind::Sand),
        (9, 30.0, PrecipitationKind::Dust),
        (7, 18.0, PrecipitationKind::Hail),
    ];
    for (layer, t, kind) in cases {
        for severity in 0..6u8 {
            let mut w = Writer::new(ByteOrder::Big);
            w.ig_control(1);
            w.weather(layer, true, severity, t, 0.0, 100.0, (14.0, 0.5, 300.0), 0);
            let packets = parse_message(&w.bytes).expect("valid");
            let Packet::WeatherControl(p) = packets[1] else {
                panic!()
            };
            let Applied::Changed(weather) = host.apply(&p) else {
                panic!("layer {layer} severity {severity}: {:?}", host.apply(&p));
            };
            assert_eq!(weather.kind, kind);
            let expected = match kind {
                PrecipitationKind::Rain => Some(RAIN_MM_PER_H[usize::from(severity)]),
                PrecipitationKind::DrySnow
                | PrecipitationKind::WetSnow
                | PrecipitationKind::Sleet => Some(SNOW_MM_PER_H[usize::from(severity)]),
                PrecipitationKind::Hail => Some(HAIL_MM_PER_H[usize::from(severity)]),
                _ => None,
            };
            if let Some(rate) = expected {
                assert!((weather.intensity_mm_per_h - rate).abs() < 1e-6);
            }
            // Visibility falls as severity rises, for every kind.
            let v = weather.visibility_m();
            assert!(v.is_finite() && v > 0.0);
            assert!((weather.relative_humidity - 0.4).abs() < 1e-6);
            // From 300°: toward +x, +z; 0.5 m/s up.
            let m = weather.wind.mean_wind_mps;
            assert!(m.x > 11.0 && m.z > 6.0 && (m.y - 0.5).abs() < 1e-6, "{m}");
        }
    }
    // A sandstorm at a given visibility holds it.
    let mut w = Writer::new(ByteOrder::Little);
    w.ig_control(2);
    w.weather(8, true, 0, 35.0, 300.0, 100.0, (16.0, 0.0, 300.0), 0);
    let Packet::WeatherControl(p) = parse_message(&w.bytes).expect("valid")[1] else {
        panic!()
    };
    let Applied::Changed(sand) = host.apply(&p) else {
        panic!()
    };
    assert!(
        (sand.visibility_m() - 300.0).abs() < 3.0,
        "{}",
        sand.visibility_m()
    );
}

#[test]
fn disabling_the_layer_clears_it_and_other_layers_and_scopes_are_ignored() {
    let mut host = HostWeather::new(Weather::default());
    let packet = |layer, enabled, scope, temperature| WeatherControl {
        entity_region_id: 0,
        layer,
        humidity_percent: 80,
        enabled,
        random_winds: false,
        cloud_type: 0,
        scope,
        severity: 2,
        air_temperature_c: temperature,
        visibility_m: 0.0,
        coverage_percent: 50.0,
        base_elevation_m: 0.0,
        thickness_m: 0.0,
        transition_band_m: 0.0,
        horizontal_wind_mps: 3.0,
        vertical_wind_mps: 0.0,
        wind_from_deg: 0.0,
    };
    let Applied::Changed(rain) = host.apply(&packet(4, true, 0, 10.0)) else {
        panic!()
    };
    assert!(
        (rain.intensity_mm_per_h - 0.5 * RAIN_MM_PER_H[2]).abs() < 1e-6,
        "coverage scales it"
    );
    assert_eq!(
        host.apply(&packet(1, true, 0, 10.0)),
        Applied::Refused,
        "a cloud layer 0 m thick"
    );
    assert_eq!(
        host.apply(&packet(0, true, 1, 10.0)),
        Applied::Ignored,
        "a region's fog"
    );
    assert_eq!(
        host.apply(&packet(4, true, 1, 10.0)),
        Applied::Ignored,
        "a region"
    );
    assert_eq!(
        host.apply(&packet(5, false, 0, 10.0)),
        Applied::Ignored,
        "another layer off"
    );
    assert_eq!(
        host.apply(&packet(5, true, 0, 30.0)),
        Applied::Refused,
        "snow at 30 °C"
    );
    assert_eq!(host.weather(), rain, "refused leaves the weather as it was");
    let Applied::Changed(clear) = host.apply(&packet(4, false, 0, 10.0)) else {
        panic!()
    };
    assert!(clear.intensity_mm_per_h.abs() < f32::MIN_POSITIVE);
}

#[test]
fn malformed_messages_are_named() {
    let good = rain_message(ByteOrder::Big, 1);
    assert!(matches!(
        parse_message(&good[..10]),
        Err(CigiError::Truncated { .. })
    ));
    assert!(matches!(
        parse_message(&good[..40]),
        Err(CigiError::Truncated { .. })
    ));
    let mut bad = good.clone();
    bad[6] = 0x12;
    assert!(matches!(
        parse_message(&bad),
        Err(CigiError::BadMagic { .. })
    ));
    let mut bad = good.clone();
    bad[2] = 4;
    assert!(matches!(
        parse_message(&bad),
        Err(CigiError::UnsupportedVersion { major_version: 4 })
    ));
    let mut bad = good.clone();
    bad[0] = 12;
    assert!(matches!(
        parse_message(&bad),
        Err(CigiError::NotIgControlFirst { .. })
    ));
    let mut bad = good.clone();
    bad[25] = 60;
    assert!(matches!(
        parse_message(&bad),
        Err(CigiError::BadSize { .. } | CigiError::Truncated { .. })
    ));
    let mut bad = good.clone();
    bad[24 + 8..24 + 12].copy_from_slice(&f32::NAN.to_be_bytes());
    assert!(matches!(
        parse_message(&bad),
        Err(CigiError::NonFinite { .. })
    ));
    // An unknown packet is skipped by its size.
    let mut other = good.clone();
    other.extend([99, 8, 0, 0, 0, 0, 0, 0]);
    let packets = parse_message(&other).expect("skips it");
    assert_eq!(packets[2], Packet::Other { opcode: 99 });
}

proptest! {
    #[test]
    fn any_bytes_are_read_or_refused_without_a_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        let _ = parse_message(&bytes);
    }

    #[test]
    fn mutated_messages_are_read_or_refused_without_a_panic(
        at in 0usize..80, value in any::<u8>(), cut in 0usize..81, little in any::<bool>(),
    ) {
        let order = if little { ByteOrder::Little } else { ByteOrder::Big };
        let mut bytes = rain_message(order, 4);
        bytes[at] = value;
        bytes.truncate(cut);
        if let Ok(packets) = parse_message(&bytes) {
            let mut host = HostWeather::new(Weather::default());
            for p in packets {
                if let Packet::WeatherControl(w) = p {
                    let _ = host.apply(&w);
                    prop_assert!(host.weather().validate().is_ok());
                }
            }
        }
    }
}

#[test]
fn start_of_frame_reads_back_in_both_byte_orders() {
    let sof = StartOfFrame {
        database: -3,
        ig_status: 0,
        ig_mode: 1,
        ig_frame: 0x0102_0304,
        timestamp_10us: 123_456,
        last_host_frame: 99,
    };
    for order in [ByteOrder::Big, ByteOrder::Little] {
        let bytes = sof.to_bytes(order);
        assert_eq!((bytes[0], bytes[1], bytes[2]), (101, 24, 3));
        // Minor version 3, timestamp valid, operate.
        assert_eq!(bytes[5], 0x35);
        assert_eq!(parse_start_of_frame(&bytes).expect("reads"), (sof, order));
    }
    assert!(matches!(
        parse_start_of_frame(&sof.to_bytes(ByteOrder::Big)[..20]),
        Err(CigiError::Truncated { .. })
    ));
}

#[test]
fn a_host_on_loopback_changes_the_weather_and_bad_datagrams_are_counted() {
    let mut receiver = CigiReceiver::bind(0, Weather::default()).expect("a free port");
    assert!(
        !receiver.send_start_of_frame(0, Duration::ZERO),
        "no host heard yet"
    );
    let port = receiver.local_addr().expect("bound").port();
    let host = UdpSocket::bind("127.0.0.1:0").expect("host socket");
    let to = ("127.0.0.1", port);
    host.send_to(&[1, 2, 3], to).expect("sent");
    host.send_to(&rain_message(ByteOrder::Little, 5), to)
        .expect("sent");
    let start = Instant::now();
    let mut weather = None;
    while weather.is_none() && start.elapsed() < Duration::from_secs(5) {
        weather = receiver.poll();
        std::thread::sleep(Duration::from_millis(5));
    }
    let weather = weather.expect("the host's rain arrives");
    assert_eq!(weather.kind, PrecipitationKind::Rain);
    assert!((weather.intensity_mm_per_h - RAIN_MM_PER_H[5]).abs() < 1e-6);
    let counts = receiver.counts();
    assert_eq!(counts.datagrams, 2);
    assert_eq!(counts.malformed, 1);
    assert_eq!((counts.ig_control, counts.weather_applied), (1, 1));
    assert!(receiver.last_error().is_some());

    // The IG answers the host that spoke, in its byte order, echoing its frame.
    assert!(receiver.send_start_of_frame(41, Duration::from_millis(25)));
    host.set_read_timeout(Some(Duration::from_secs(5)))
        .expect("timeout");
    let mut buffer = [0u8; 64];
    let (len, _) = host.recv_from(&mut buffer).expect("Start of Frame arrives");
    let (sof, order) = parse_start_of_frame(&buffer[..len]).expect("well formed");
    assert_eq!(order, ByteOrder::Little);
    assert_eq!(
        (sof.ig_frame, sof.timestamp_10us, sof.ig_mode),
        (41, 2_500, 1)
    );
    assert_eq!(sof.last_host_frame, RAIN_HOST_FRAME);
    assert_eq!(receiver.counts().start_of_frame_sent, 1);
}

#[test]
fn the_ground_fog_layer_is_fog_up_to_its_top_and_only_news_is_announced() {
    let mut receiver = CigiReceiver::bind(0, Weather::default()).expect("a free port");
    let port = receiver.local_addr().expect("bound").port();
    let host = UdpSocket::bind("127.0.0.1:0").expect("host socket");
    let fog_message = |enabled: bool, visibility_m: f32| {
        let mut w = Writer::new(ByteOrder::Big);
        w.ig_control(7);
        // Base 800 m, thickness 1 500 m (the writer's): the top at 2 300 m.
        w.weather(0, enabled, 3, 5.0, visibility_m, 100.0, (2.0, 0.0, 90.0), 0);
        w.bytes
    };
    let mut deliver = |bytes: Vec<u8>| {
        let before = receiver.counts().datagrams;
        host.send_to(&bytes, ("127.0.0.1", port)).expect("sent");
        let start = Instant::now();
        while receiver.counts().datagrams == before && start.elapsed() < Duration::from_secs(5) {
            assert_eq!(receiver.poll(), None, "fog is not a weather change");
            std::thread::sleep(Duration::from_millis(5));
        }
        receiver.take_fog_layer()
    };
    assert_eq!(
        deliver(fog_message(true, 150.0)),
        Some(Some(FogLayer::new(2_300.0, 150.0)))
    );
    assert_eq!(
        deliver(fog_message(true, 150.0)),
        None,
        "a repeat is no news"
    );
    // No visibility sent: severity 3's.
    assert_eq!(
        deliver(fog_message(true, 0.0)),
        Some(Some(FogLayer::new(2_300.0, FOG_VISIBILITY_M[3])))
    );
    assert_eq!(deliver(fog_message(false, 0.0)), Some(None), "cleared");

    let mut weather = HostWeather::new(Weather::default());
    let refused = WeatherControl {
        entity_region_id: 0,
        layer: 0,
        humidity_percent: 80,
        enabled: true,
        random_winds: false,
        cloud_type: 0,
        scope: 0,
        severity: 2,
        air_temperature_c: 5.0,
        visibility_m: f32::NAN,
        coverage_percent: 100.0,
        base_elevation_m: 0.0,
        thickness_m: 30.0,
        transition_band_m: 0.0,
        horizontal_wind_mps: 0.0,
        vertical_wind_mps: 0.0,
        wind_from_deg: 0.0,
    };
    assert_eq!(
        weather.apply(&refused),
        Applied::Fog(Some(FogLayer::new(30.0, FOG_VISIBILITY_M[2]))),
        "NaN is not above 0: the severity's visibility"
    );
    let too_high = WeatherControl {
        base_elevation_m: 1.0e9,
        ..refused
    };
    assert_eq!(weather.apply(&too_high), Applied::Refused);
    assert_eq!(
        weather.fog_layer(),
        Some(FogLayer::new(30.0, FOG_VISIBILITY_M[2]))
    );
    assert_eq!(
        weather.weather(),
        Weather::default(),
        "fog leaves the precipitation"
    );
}

#[test]
fn cloud_layers_one_to_three_are_drawn_together_lowest_first() {
    use precip_model::drawing::clouds::{CloudKind, CloudLayer, CloudLayers};
    let mut host = HostWeather::new(Weather::default());
    let layer = |id: u8, enabled: bool, cloud_type: u8, base: f32, coverage: f32| WeatherControl {
        entity_region_id: 0,
        layer: id,
        humidity_percent: 70,
        enabled,
        random_winds: false,
        cloud_type,
        scope: 0,
        severity: 0,
        air_temperature_c: 10.0,
        visibility_m: 0.0,
        coverage_percent: coverage,
        base_elevation_m: base,
        thickness_m: 1_200.0,
        transition_band_m: 0.0,
        horizontal_wind_mps: 0.0,
        vertical_wind_mps: 0.0,
        wind_from_deg: 0.0,
    };
    let cumulus = CloudLayer {
        base_m: 1_500.0,
        thickness_m: 1_200.0,
        coverage: 0.4,
        kind: CloudKind::Cumulus,
        transition_band_m: 0.0,
    };
    assert_eq!(
        host.apply(&layer(2, true, 7, 1_500.0, 40.0)),
        Applied::Clouds(CloudLayers::one(cumulus))
    );
    // The transition band is the layer's; a negative one is refused.
    let banded = WeatherControl {
        transition_band_m: 250.0,
        ..layer(2, true, 7, 1_500.0, 40.0)
    };
    assert_eq!(
        host.apply(&banded),
        Applied::Clouds(CloudLayers::one(CloudLayer {
            transition_band_m: 250.0,
            ..cumulus
        }))
    );
    let negative = WeatherControl {
        transition_band_m: -5.0,
        ..banded
    };
    assert_eq!(host.apply(&negative), Applied::Refused);
    assert_eq!(
        host.apply(&layer(2, true, 7, 1_500.0, 40.0)),
        Applied::Clouds(CloudLayers::one(cumulus))
    );
    // A stratus sheet on layer 1 reaching into the cumulus (400 … 1 600 m) is
    // drawn below it, ending at the cumulus' base; both are drawn, lowest first.
    let stratus = CloudLayer {
        base_m: 300.0,
        coverage: 0.9,
        kind: CloudKind::Stratus,
        ..cumulus
    };
    let two = host.apply(&layer(1, true, 10, 300.0, 90.0));
    let Applied::Clouds(two) = two else {
        panic!("{two:?}");
    };
    assert_eq!(two.iter().copied().collect::<Vec<_>>(), [stratus, cumulus]);
    // An altostratus (type 2: a sheet) on layer 3 at 2 000 m starts at the
    // cumulus' top, 2 700 m; below 10 m left it would not be drawn.
    let Applied::Clouds(three) = host.apply(&layer(3, true, 2, 2_000.0, 100.0)) else {
        panic!("three layers");
    };
    let top = three.iter().nth(2).copied().expect("a third layer");
    assert_eq!((top.base_m, top.thickness_m), (2_700.0, 500.0));
    assert_eq!(
        host.apply(&layer(3, true, 2, 1_500.0, 100.0)),
        Applied::Clouds(two),
        "a sheet wholly inside the cumulus is not drawn"
    );
    assert_eq!(
        host.apply(&layer(3, false, 2, 1_500.0, 100.0)),
        Applied::Clouds(two)
    );
    assert_eq!(
        host.apply(&layer(1, false, 10, 300.0, 90.0)),
        Applied::Clouds(CloudLayers::one(cumulus))
    );
    assert_eq!(
        host.apply(&layer(2, false, 7, 1_500.0, 40.0)),
        Applied::Clouds(CloudLayers::NONE)
    );
    assert_eq!(
        host.apply(&layer(3, true, 6, f32::INFINITY, 40.0)),
        Applied::Refused
    );
    assert!(host.cloud_layers().is_empty());
    assert_eq!(
        host.weather(),
        Weather::default(),
        "clouds leave the precipitation"
    );
    // The type travels in the flags' high bits.
    let mut w = Writer::new(ByteOrder::Big);
    w.ig_control(1);
    let start = w.bytes.len();
    w.weather(2, true, 0, 10.0, 0.0, 50.0, (0.0, 0.0, 0.0), 0);
    w.bytes[start + 6] |= 6 << 4;
    let Packet::WeatherControl(p) = parse_message(&w.bytes).expect("valid")[1] else {
        panic!()
    };
    assert_eq!(p.cloud_type, 6);
    assert_eq!(
        host.apply(&p),
        Applied::Clouds(CloudLayers::one(CloudLayer {
            base_m: 800.0,
            thickness_m: 1_500.0,
            coverage: 0.5,
            kind: CloudKind::Cumulonimbus,
            // The writer's band (its offset 32, between thickness and wind).
            transition_band_m: 100.0,
        }))
    );
}

#[test]
fn a_host_flies_the_eyepoint_in_either_byte_order_and_the_ig_keeps_step() {
    use glam::Vec3;
    use precip_cigi::GeodeticOrigin;
    let origin = GeodeticOrigin {
        latitude_deg: 47.0,
        longitude_deg: 8.0,
        altitude_m: 400.0,
    };
    for order in [ByteOrder::Big, ByteOrder::Little] {
        let mut receiver = CigiReceiver::bind(0, Weather::default()).expect("a free port");
        receiver.set_view(origin, 0);
        let port = receiver.local_addr().expect("bound").port();
        let host = UdpSocket::bind("127.0.0.1:0").expect("host socket");
        let send = |frame: u32, build: &dyn Fn(&mut Writer)| {
            let mut w = Writer::new(order);
            w.ig_control(frame);
            build(&mut w);
            host.send_to(&w.bytes, ("127.0.0.1", port)).expect("sent");
        };
        // Frame 1: the ownship 300 m above the origin heading east, a packet precip
        // does not use (Sensor Control, opcode 17, 24 bytes), and the date and time
        // (Celestial Sphere Control: 11:30 UTC, ephemeris and date valid, 21 June
        // 2026 as MMDDYYYY).
        send(1, &|w| {
            w.entity(0, [0.0, 0.0, 90.0], [47.0, 8.0, 700.0]);
            w.bytes.extend([17u8, 24]);
            w.bytes.extend([0u8; 22]);
            w.bytes.extend([9u8, 16, 11, 30, 0x13, 0, 0, 0]);
            w.u32(6_212_026);
            w.f32(0.0);
        });
        assert!(
            receiver.wait_for_host_frame(Duration::from_secs(5)),
            "{order:?}"
        );
        let eye = receiver.take_eyepoint(16.0 / 9.0).expect("placed");
        assert!((eye.position_m - Vec3::new(0.0, 300.0, 0.0)).length() < 1e-3);
        assert!((eye.forward - Vec3::X).length() < 1e-5, "{eye:?}");
        assert_eq!(receiver.take_eyepoint(1.0), None, "only news");
        // The solstice's solar noon at 47° N 8° E: 66° up, due south (+z).
        let sun = receiver.take_sun().expect("placed");
        assert!(
            (sun.y.asin().to_degrees() - 66.4).abs() < 0.6 && sun.z > 0.9 * sun.z.hypot(sun.x),
            "{sun}"
        );
        assert_eq!(receiver.take_sun(), None, "only news");
        // Nothing new: the wait times out.
        assert!(!receiver.wait_for_host_frame(Duration::from_millis(50)));
        // Frame 2: 0.01° further east, a pilot's eye looking 10° down, 60° × 40°.
        send(2, &|w| {
            w.entity(0, [0.0, 0.0, 90.0], [47.0, 8.01, 700.0]);
            w.view_control(0, [2.0, 0.0, -1.0, 0.0, -10.0, 0.0]);
            w.view_definition([-30.0, 30.0, 20.0, -20.0]);
        });
        assert!(receiver.wait_for_host_frame(Duration::from_secs(5)));
        let eye = receiver.take_eyepoint(1.5).expect("moved");
        assert!(
            (eye.position_m.x - 762.5).abs() < 0.5 && (eye.position_m.y - 300.9).abs() < 0.1,
            "{eye:?}"
        );
        assert!(
            (eye.forward.y + 10f32.to_radians().sin()).abs() < 1e-5,
            "{eye:?}"
        );
        let fov = eye.vertical_fov_rad.expect("defined");
        assert!((fov - 40f32.to_radians()).abs() < 1e-5);
        let counts = receiver.counts();
        assert_eq!(
            (counts.entity_control, counts.view_control, counts.other),
            (2, 2, 1),
            "{order:?}"
        );
        assert_eq!(receiver.other_opcodes().get(&17), Some(&1));
        assert_eq!(receiver.counts().celestial, 1);
        assert_eq!(receiver.weather(), Weather::default());
    }
}
