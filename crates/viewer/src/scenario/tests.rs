//! Scenarios as simulators write them: environments in the Init, in events at
//! simulation times, in catalogs, with parameters and expressions.

use std::path::Path;

use glam::Vec3;
use precip_model::PrecipitationKind;
use precip_model::drawing::clouds::{CloudKind, CloudLayer};
use precip_model::drawing::fog_layer::FogLayer;

use super::*;

fn xosc(environment: &str) -> String {
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2026-11-25T00:00:00" description="t" author="t"/>
  <Storyboard>
<Init><Actions><GlobalAction><EnvironmentAction>
  {environment}
</EnvironmentAction></GlobalAction></Actions></Init>
  </Storyboard>
</OpenSCENARIO>"#
    )
}

fn read(environment: &str) -> Result<ScenarioWeather, ScenarioError> {
    scenario_from_text(&xosc(environment), Path::new("t.xosc")).map(|s| s.initial)
}

#[test]
fn cloud_cover_in_oktas_or_as_a_state_is_a_cloud_layer() {
    let w = read(
        r#"<Environment name="c"><Weather temperature="290" fractionalCloudCover="threeOktas">
             <Precipitation precipitationType="dry"/></Weather></Environment>"#,
    )
    .expect("valid");
    assert_eq!(
        w.cloud_layer,
        Some(CloudLayer::typical(CloudKind::Cumulus, 0.375))
    );
    let rainy = read(
        r#"<Environment name="r"><Weather cloudState="rainy">
             <Precipitation precipitationType="rain" intensity="0.5"/></Weather></Environment>"#,
    )
    .expect("valid");
    assert_eq!(
        rainy.cloud_layer,
        Some(CloudLayer::typical(CloudKind::Nimbostratus, 1.0))
    );
    assert_eq!(cloud_layer_of(None, Some("free"), false), None);
    assert_eq!(cloud_layer_of(Some("zeroOktas"), Some("rainy"), true), None);
    assert_eq!(
        cloud_layer_of(Some("eightOktas"), None, true),
        Some(CloudLayer::typical(CloudKind::Nimbostratus, 1.0))
    );
    assert_eq!(
        cloud_layer_of(None, Some("overcast"), false),
        Some(CloudLayer::typical(CloudKind::Stratus, 1.0))
    );
}

#[test]
fn a_fog_with_a_bounding_box_is_a_layer_up_to_its_top() {
    let w = read(
        r#"<Environment name="valley"><Weather temperature="278.15">
             <Fog visualRange="150">
               <BoundingBox>
                 <Center x="0" y="0" z="10"/>
                 <Dimensions width="2000" length="2000" height="30"/>
               </BoundingBox>
             </Fog>
             <Precipitation precipitationType="dry"/>
           </Weather></Environment>"#,
    )
    .expect("valid");
    assert_eq!(w.fog_layer, Some(FogLayer::new(25.0, 150.0)));
    assert_eq!(
        w.fog_extinction_per_m, None,
        "the layer, not a uniform haze"
    );
    let bad = read(
        r#"<Environment name="v"><Weather><Fog visualRange="150"><BoundingBox>
             <Center x="0" y="0" z="high"/><Dimensions width="1" length="1" height="30"/>
           </BoundingBox></Fog><Precipitation precipitationType="dry"/></Weather></Environment>"#,
    )
    .expect_err("z is not a number");
    assert!(bad.to_string().contains("Center"), "{bad}");
}

#[test]
fn rain_snow_wind_and_fog_of_openscenario_one_one() {
    let w = read(
        r#"<Environment name="wet">
             <TimeOfDay animation="false" dateTime="2026-11-25T12:00:00"/>
             <Weather temperature="283.15" fractionalCloudCover="eightOktas">
               <Sun azimuth="0" elevation="1" illuminance="1000"/>
               <Fog visualRange="800"/>
               <Precipitation precipitationType="rain" precipitationIntensity="7.5"/>
               <Wind direction="1.5707963" speed="6"/>
             </Weather>
             <RoadCondition frictionScaleFactor="0.7"/>
           </Environment>"#,
    )
    .expect("valid");
    assert_eq!(w.weather.kind, PrecipitationKind::Rain);
    assert!((w.weather.intensity_mm_per_h - 7.5).abs() < 1e-6);
    assert!((w.weather.air_temperature_c - 10.0).abs() < 1e-3);
    // Toward +y (north) is precip's −z.
    let m = w.weather.wind.mean_wind_mps;
    assert!(m.x.abs() < 1e-4 && (m.z + 6.0).abs() < 1e-4, "{m}");
    assert!((w.fog_extinction_per_m.expect("fog") - 3.912 / 800.0).abs() < 1e-7);

    let snow = read(
        r#"<Environment name="s"><Weather temperature="263.15">
             <Precipitation precipitationType="snow" precipitationIntensity="2"/>
           </Weather></Environment>"#,
    )
    .expect("valid");
    assert_eq!(snow.weather.kind, PrecipitationKind::DrySnow);
    let wet = read(
        r#"<Environment name="s"><Weather temperature="273.65">
             <Precipitation precipitationType="snow" intensity="0.5"/>
           </Weather></Environment>"#,
    )
    .expect("1.0's intensity");
    assert_eq!(wet.weather.kind, PrecipitationKind::WetSnow);
    assert!((wet.weather.intensity_mm_per_h - 5.0).abs() < 1e-6);
    let dry = read(
        r#"<Environment name="d"><Weather><Precipitation precipitationType="dry"/></Weather></Environment>"#,
    )
    .expect("dry");
    assert!(dry.weather.intensity_mm_per_h.abs() < f32::MIN_POSITIVE);
}

#[test]
fn missing_and_out_of_range_values_are_named() {
    let err = |env: &str| read(env).expect_err("refused").to_string();
    assert!(err("").contains("no Environment/Weather"));
    assert!(
        err(r#"<Environment name="x"><Weather><Precipitation precipitationType="hail" precipitationIntensity="1"/></Weather></Environment>"#)
            .contains("precipitationType")
    );
    assert!(
        err(r#"<Environment name="x"><Weather temperature="20"><Precipitation precipitationType="rain" precipitationIntensity="1"/></Weather></Environment>"#)
            .contains("temperature")
    );
    assert!(
        err(r#"<Environment name="x"><Weather><Precipitation precipitationType="rain" precipitationIntensity="-3"/></Weather></Environment>"#)
            .contains("precipitationIntensity")
    );
    assert!(
        err(r#"<Environment name="x"><Weather><Precipitation precipitationType="rain"/></Weather></Environment>"#)
            .contains("missing")
    );
    assert!(
        err(r#"<Environment name="x"><Weather><Fog visualRange="fog"/><Precipitation precipitationType="dry"/></Weather></Environment>"#)
            .contains("visualRange")
    );
    assert!(
        err(r#"<Environment name="x"><Weather temperature="303.15"><Precipitation precipitationType="snow" precipitationIntensity="1"/></Weather></Environment>"#)
            .contains("°C")
    );
    let broken = scenario_from_text("<OpenSCENARIO><Environment>", Path::new("b.xosc"));
    assert!(broken.is_err());
}

/// A storyboard: Init dry, rain at 10 s, snow 3 s after the act that starts at 10
/// s, an environment waiting on a car, a fog whose range is a parameter.
const TIMELINE: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-11-26T00:00:00" description="t" author="t"/>
  <ParameterDeclarations>
    <ParameterDeclaration name="FogVisualRange" parameterType="double" value="800"/>
    <ParameterDeclaration name="RainRate" parameterType="double" value="${$FogVisualRange / 160}"/>
  </ParameterDeclarations>
  <Storyboard>
    <Init><Actions>
      <GlobalAction><EnvironmentAction><Environment name="Dry">
        <TimeOfDay animation="false" dateTime="2026-11-26T08:00:00"/>
        <Weather temperature="285">
          <Sun azimuth="1.5707963" elevation="0.5236" illuminance="20000"/>
          <Fog visualRange="$FogVisualRange"/>
          <Precipitation precipitationType="dry"/>
        </Weather>
        <RoadCondition frictionScaleFactor="0.9"/>
      </Environment></EnvironmentAction></GlobalAction>
      <Private entityRef="Ego"><PrivateAction><TeleportAction/></PrivateAction></Private>
    </Actions></Init>
    <Story name="Weather">
      <Act name="Change">
        <ManeuverGroup maximumExecutionCount="1" name="G">
          <Actors selectTriggeringEntities="false"/>
          <Maneuver name="M">
            <Event name="Rain" priority="override">
              <Action name="A"><GlobalAction><EnvironmentAction><Environment name="Wet">
                <Weather temperature="284"><Precipitation precipitationType="rain" precipitationIntensity="$RainRate"/></Weather>
              </Environment></EnvironmentAction></GlobalAction></Action>
              <StartTrigger><ConditionGroup><Condition name="t" delay="0" conditionEdge="rising">
                <ByValueCondition><SimulationTimeCondition value="10" rule="greaterThan"/></ByValueCondition>
              </Condition></ConditionGroup></StartTrigger>
            </Event>
            <Event name="Snow" priority="override">
              <Action name="A"><GlobalAction><EnvironmentAction><Environment name="Cold">
                <Weather temperature="268"><Precipitation precipitationType="snow" precipitationIntensity="2"/></Weather>
              </Environment></EnvironmentAction></GlobalAction></Action>
              <StartTrigger>
                <ConditionGroup><Condition name="near" delay="0" conditionEdge="rising">
                  <ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/></TriggeringEntities>
                    <EntityCondition><ReachPositionCondition tolerance="2"><Position/></ReachPositionCondition></EntityCondition>
                  </ByEntityCondition>
                </Condition></ConditionGroup>
                <ConditionGroup><Condition name="t" delay="1" conditionEdge="rising">
                  <ByValueCondition><SimulationTimeCondition value="2" rule="greaterThan"/></ByValueCondition>
                </Condition></ConditionGroup>
              </StartTrigger>
            </Event>
            <Event name="WhenTheCarArrives" priority="override">
              <Action name="A"><GlobalAction><EnvironmentAction><Environment name="Clear">
                <Weather><Precipitation precipitationType="dry"/></Weather>
              </Environment></EnvironmentAction></GlobalAction></Action>
              <StartTrigger><ConditionGroup><Condition name="near" delay="0" conditionEdge="rising">
                <ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/></TriggeringEntities>
                  <EntityCondition><ReachPositionCondition tolerance="2"><Position/></ReachPositionCondition></EntityCondition>
                </ByEntityCondition>
              </Condition></ConditionGroup></StartTrigger>
            </Event>
            <Event name="Overtake" priority="override">
              <Action name="A"><PrivateAction/></Action>
            </Event>
          </Maneuver>
        </ManeuverGroup>
        <StartTrigger><ConditionGroup><Condition name="act" delay="0" conditionEdge="rising">
          <ByValueCondition><SimulationTimeCondition value="$ActStart" rule="greaterThan"/></ByValueCondition>
        </Condition></ConditionGroup></StartTrigger>
      </Act>
      <ParameterDeclarations>
        <ParameterDeclaration name="ActStart" parameterType="double" value="3"/>
      </ParameterDeclarations>
    </Story>
  </Storyboard>
</OpenSCENARIO>"#;

#[test]
fn parameters_and_expressions_resolve_and_events_change_the_weather_at_their_times() {
    let s = scenario_from_text(TIMELINE, Path::new("t.xosc")).expect("valid");
    // The Init: dry, the fog's range a parameter, the sun due east 30° up.
    assert!(s.initial.weather.intensity_mm_per_h.abs() < f32::MIN_POSITIVE);
    assert!((s.initial.fog_extinction_per_m.expect("fog") - 3.912 / 800.0).abs() < 1e-7);
    let sun = s.initial.to_sun.expect("a sun");
    assert!((sun - Vec3::new(0.866, 0.5, 0.0)).length() < 1e-3, "{sun}");
    assert_eq!(s.initial.friction_scale, Some(0.9));
    assert_eq!(
        s.initial.time_of_day.as_deref(),
        Some("2026-11-26T08:00:00")
    );
    // Rain at 10 s (its rate an expression of a parameter: 800/160 = 5 mm/h); snow
    // when its second group fires, 2 s + 1 s of delay, but not before its act (3 s;
    // the act's start a story parameter).
    let at: Vec<(f64, &str)> = s
        .changes
        .iter()
        .map(|c| (c.at_s, c.event.as_str()))
        .collect();
    assert_eq!(
        at,
        [(3.0, "Weather/Change/Snow"), (10.0, "Weather/Change/Rain")]
    );
    let rain = &s.changes[1].weather.weather;
    assert_eq!(rain.kind, PrecipitationKind::Rain);
    assert!((rain.intensity_mm_per_h - 5.0).abs() < 1e-6);
    assert_eq!(
        s.changes[0].weather.weather.kind,
        PrecipitationKind::DrySnow
    );
    // The event waiting on the car is named.
    assert_eq!(s.notes.len(), 1, "{:?}", s.notes);
    assert!(
        s.notes[0].contains("WhenTheCarArrives")
            && s.notes[0].contains("ByEntityCondition/ReachPositionCondition"),
        "{:?}",
        s.notes
    );
    // An undeclared parameter is named with its element.
    let e = scenario_from_text(&TIMELINE.replace("$RainRate", "$Rate"), Path::new("t.xosc"))
        .expect_err("undeclared");
    let text = e.to_string();
    assert!(
        text.contains("Precipitation@precipitationIntensity") && text.contains("$Rate"),
        "{text}"
    );
}

#[test]
fn an_environment_comes_from_a_catalog_with_its_parameters_assigned() {
    let dir = std::env::temp_dir().join(format!("precip-xosc-catalog-{}", std::process::id()));
    let catalogs = dir.join("Catalogs/Environments");
    std::fs::create_dir_all(&catalogs).expect("dirs");
    std::fs::write(
        catalogs.join("EnvironmentCatalog.xosc"),
        r#"<?xml version="1.0"?>
<OpenSCENARIO><FileHeader revMajor="1" revMinor="0" date="2026-11-26T00:00:00" description="c" author="t"/>
  <Catalog name="EnvironmentCatalog">
    <Environment name="Sunny"><Weather cloudState="free"><Precipitation precipitationType="dry" intensity="0"/></Weather></Environment>
    <Environment name="Rainy">
      <ParameterDeclarations><ParameterDeclaration name="Intensity" parameterType="double" value="0.2"/></ParameterDeclarations>
      <Weather cloudState="rainy"><Precipitation precipitationType="rain" intensity="$Intensity"/></Weather>
    </Environment>
  </Catalog>
</OpenSCENARIO>"#,
    )
    .expect("catalog");
    let scenario = |entry: &str, assignments: &str| {
        format!(
            r#"<OpenSCENARIO><FileHeader revMajor="1" revMinor="0" date="2026-11-26T00:00:00" description="s" author="t"/>
  <ParameterDeclarations><ParameterDeclaration name="Heavy" parameterType="double" value="0.8"/></ParameterDeclarations>
  <CatalogLocations><EnvironmentCatalog><Directory path="Catalogs/Environments"/></EnvironmentCatalog></CatalogLocations>
  <Storyboard><Init><Actions><GlobalAction><EnvironmentAction>
    <CatalogReference catalogName="EnvironmentCatalog" entryName="{entry}">{assignments}</CatalogReference>
  </EnvironmentAction></GlobalAction></Actions></Init></Storyboard>
</OpenSCENARIO>"#
        )
    };
    let file = dir.join("s.xosc");
    // The second entry, not the first; its default intensity 0.2 of 10 mm/h.
    let rainy = scenario_from_text(&scenario("Rainy", ""), &file).expect("found");
    assert!((rainy.initial.weather.intensity_mm_per_h - 2.0).abs() < 1e-5);
    assert_eq!(
        rainy.initial.cloud_layer,
        Some(CloudLayer::typical(CloudKind::Nimbostratus, 1.0))
    );
    // Assigned from the scenario's own parameter.
    let heavy = scenario_from_text(
        &scenario(
            "Rainy",
            r#"<ParameterAssignments><ParameterAssignment parameterRef="Intensity" value="$Heavy"/></ParameterAssignments>"#,
        ),
        &file,
    )
    .expect("assigned");
    assert!((heavy.initial.weather.intensity_mm_per_h - 8.0).abs() < 1e-5);
    let missing = scenario_from_text(&scenario("Foggy", ""), &file).expect_err("no entry");
    assert!(
        missing.to_string().contains("entryName=\"Foggy\""),
        "{missing}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_time_of_day_places_the_sun_where_no_sun_is_given() {
    let text = TIMELINE.replace(
        r#"<Sun azimuth="1.5707963" elevation="0.5236" illuminance="20000"/>"#,
        "",
    );
    let mut s = scenario_from_text(&text, Path::new("t.xosc")).expect("valid");
    assert_eq!(s.initial.to_sun, None);
    // Zürich, 26 November, 08:00 UTC (09:00 there): the sun some 9° up in the
    // south-east, an hour and a half after it rose.
    s.light_by_time_of_day(47.4, 8.5).expect("a date");
    let sun = s.initial.to_sun.expect("placed");
    let elevation = sun.y.asin().to_degrees();
    assert!((elevation - 9.2).abs() < 1.5, "{elevation}");
    assert!(sun.x > 0.0 && sun.z > 0.0, "south-east: {sun}");
    // The events without a TimeOfDay keep theirs (none).
    assert!(s.changes.iter().all(|c| c.weather.to_sun.is_none()));
    let bad = TIMELINE
        .replace(
            r#"<Sun azimuth="1.5707963" elevation="0.5236" illuminance="20000"/>"#,
            "",
        )
        .replace("2026-11-26T08:00:00", "the morning");
    let mut s = scenario_from_text(&bad, Path::new("t.xosc")).expect("read");
    let e = s.light_by_time_of_day(0.0, 0.0).expect_err("not a date");
    assert!(
        e.contains("TimeOfDay@dateTime") && e.contains("the morning"),
        "{e}"
    );
}
