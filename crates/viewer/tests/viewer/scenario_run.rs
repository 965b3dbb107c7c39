//! An OpenSCENARIO storyboard drives a headless run: the weather changes at the
//! simulation times its events name, and the summary says when.

use crate::cli::{gpu_or_skip, precip, temp_dir};

const STORYBOARD: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-11-26T00:00:00" description="rain at 2 s" author="precip"/>
  <ParameterDeclarations>
    <ParameterDeclaration name="RainStarts" parameterType="double" value="2"/>
  </ParameterDeclarations>
  <Storyboard>
    <Init><Actions><GlobalAction><EnvironmentAction><Environment name="Dry">
      <Weather temperature="285"><Precipitation precipitationType="dry"/></Weather>
    </Environment></EnvironmentAction></GlobalAction></Actions></Init>
    <Story name="S"><Act name="A">
      <ManeuverGroup maximumExecutionCount="1" name="G"><Actors selectTriggeringEntities="false"/>
        <Maneuver name="M"><Event name="Rain" priority="override">
          <Action name="R"><GlobalAction><EnvironmentAction><Environment name="Wet">
            <Weather temperature="284"><Precipitation precipitationType="rain" precipitationIntensity="${$RainStarts * 10}"/></Weather>
          </Environment></EnvironmentAction></GlobalAction></Action>
          <StartTrigger><ConditionGroup><Condition name="t" delay="0" conditionEdge="rising">
            <ByValueCondition><SimulationTimeCondition value="$RainStarts" rule="greaterThan"/></ByValueCondition>
          </Condition></ConditionGroup></StartTrigger>
        </Event></Maneuver>
      </ManeuverGroup>
      <StartTrigger><ConditionGroup><Condition name="a" delay="0" conditionEdge="rising">
        <ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition>
      </Condition></ConditionGroup></StartTrigger>
    </Act></Story>
  </Storyboard>
</OpenSCENARIO>"#;

#[test]
fn a_storyboard_changes_the_weather_of_a_headless_run_at_its_time() {
    if !gpu_or_skip("a_storyboard_changes_the_weather_of_a_headless_run_at_its_time") {
        return;
    }
    let dir = temp_dir("scenario-run");
    let file = dir.join("rain_at_2s.xosc");
    std::fs::write(&file, STORYBOARD).expect("scenario");
    let out = precip()
        .args([
            "--frames",
            "6",
            "--dt",
            "0.5",
            "--size",
            "64x36",
            "--particles",
            "5000",
        ])
        .arg("--scenario")
        .arg(&file)
        .arg("--out")
        .arg(dir.join("frames"))
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    // Frame 4 starts at 2.0 s: the rain of 20 mm/h (the expression) begins there.
    assert!(
        text.contains("scenario: at 2.0 s (2 s due) S/A/Rain: Rain 20.00 mm/h"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
