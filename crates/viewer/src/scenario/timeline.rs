//! The weather's timeline in a storyboard: the `Init`'s `EnvironmentAction` from the
//! start, then every `Event` of a `Story`'s `Act/ManeuverGroup/Maneuver` whose
//! `Action/GlobalAction/EnvironmentAction` sets an environment, at the time its
//! start trigger fires.
//!
//! Triggers are followed where they are simulation time: a `ConditionGroup` fires
//! when all its conditions are true (the latest), a trigger when any group does
//! (the earliest); a `SimulationTimeCondition` with `greaterThan`, `greaterOrEqual`
//! or `equalTo` is true from its `value` (s), one with `lessThan`, `lessOrEqual` or
//! `notEqualTo` from the start; each condition's `delay` adds. An event starts no
//! earlier than its act. An environment whose trigger waits on anything else (an
//! entity reaching a place, a storyboard state, …) is not applied and is named in
//! [`Scenario::notes`].

use std::path::Path;

use roxmltree::Node;

use super::ScenarioError;
use super::catalogs::Catalogs;
use super::environment::{ScenarioWeather, environment_weather};
use super::parameters::Parameters;

/// An environment that takes effect at a simulation time.
#[derive(Debug, Clone, PartialEq)]
pub struct TimedWeather {
    /// When, s of simulation time.
    pub at_s: f64,
    /// The event that sets it (`Story/Act/Event` names).
    pub event: String,
    /// What it sets.
    pub weather: ScenarioWeather,
}

/// A scenario's weather over time.
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    /// From the start.
    pub initial: ScenarioWeather,
    /// Later changes, in time order.
    pub changes: Vec<TimedWeather>,
    /// What was read but not applied, and why.
    pub notes: Vec<String>,
}

impl Scenario {
    /// Each environment's light from its `TimeOfDay` where it names no `Sun`: the
    /// sun's direction at that time seen from `latitude_deg`, `longitude_deg` (the
    /// scene's origin; precip_model::weather::sun). A `dateTime` that is not one is
    /// an error naming it.
    pub fn light_by_time_of_day(
        &mut self,
        latitude_deg: f64,
        longitude_deg: f64,
    ) -> Result<(), String> {
        let weathers = std::iter::once(&mut self.initial)
            .chain(self.changes.iter_mut().map(|c| &mut c.weather));
        for w in weathers {
            if let (None, Some(text)) = (w.to_sun, &w.time_of_day) {
                let time = precip_model::weather::sun::UtcTime::parse_iso8601(text)
                    .map_err(|e| format!("TimeOfDay@dateTime: {e}"))?;
                w.to_sun = Some(precip_model::weather::sun::to_sun_at(
                    &time,
                    latitude_deg,
                    longitude_deg,
                ));
            }
        }
        Ok(())
    }
}

fn children<'a, 'i: 'a>(node: Node<'a, 'i>, tag: &'a str) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(move |c| c.has_tag_name(tag))
}

fn child<'a, 'i>(node: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    node.children().find(|c| c.has_tag_name(tag))
}

/// Everything the scenario's document `root` says about the weather (`file` names
/// it in errors; catalogs are found from its folder).
pub fn scenario_of(root: Node<'_, '_>, file: &Path) -> Result<Scenario, ScenarioError> {
    let parameter_error = |problem: String| ScenarioError::Parameter {
        file: file.to_path_buf(),
        problem,
    };
    let parameters =
        Parameters::declared_in(root, &Parameters::default()).map_err(parameter_error)?;
    let folder = file.parent().unwrap_or_else(|| Path::new("."));
    let catalogs = Catalogs::of(root, folder, &parameters, file)?;
    let environment_of = |action: Node<'_, '_>, scope: &Parameters| {
        if let Some(environment) = child(action, "Environment") {
            let own = Parameters::declared_in(environment, scope).map_err(parameter_error)?;
            return environment_weather(environment, &own, file).map(Some);
        }
        match child(action, "CatalogReference") {
            Some(reference) => catalogs.environment(reference, scope, file).map(Some),
            None => Ok(None),
        }
    };
    let mut notes = Vec::new();
    let storyboard = child(root, "Storyboard");
    let mut initial = None;
    if let Some(init) = storyboard.and_then(|s| child(s, "Init")) {
        for action in init
            .descendants()
            .filter(|n| n.has_tag_name("EnvironmentAction"))
        {
            if let Some(w) = environment_of(action, &parameters)? {
                initial = Some(w);
            }
        }
    }
    let mut changes = Vec::new();
    for story in storyboard.into_iter().flat_map(|s| children(s, "Story")) {
        let story_scope = Parameters::declared_in(story, &parameters).map_err(parameter_error)?;
        let story_name = story.attribute("name").unwrap_or("?");
        for act in children(story, "Act") {
            let act_name = act.attribute("name").unwrap_or("?");
            let act_time = trigger_time(child(act, "StartTrigger"), &story_scope);
            for maneuver in children(act, "ManeuverGroup").flat_map(|g| children(g, "Maneuver")) {
                let scope =
                    Parameters::declared_in(maneuver, &story_scope).map_err(parameter_error)?;
                for event in children(maneuver, "Event") {
                    let name = format!(
                        "{story_name}/{act_name}/{}",
                        event.attribute("name").unwrap_or("?")
                    );
                    let actions = children(event, "Action")
                        .filter_map(|a| child(a, "GlobalAction"))
                        .filter_map(|g| child(g, "EnvironmentAction"));
                    let mut weathers = Vec::new();
                    for action in actions {
                        if let Some(w) = environment_of(action, &scope)? {
                            weathers.push(w);
                        }
                    }
                    if weathers.is_empty() {
                        continue;
                    }
                    let when = act_time.clone().and_then(|act_s| {
                        trigger_time(child(event, "StartTrigger"), &scope)
                            .map(|event_s| act_s.max(event_s))
                    });
                    match when {
                        Ok(at_s) => changes.extend(weathers.into_iter().map(|weather| {
                            TimedWeather {
                                at_s,
                                event: name.clone(),
                                weather,
                            }
                        })),
                        Err(why) => notes.push(format!(
                            "the environment of event {name} is not applied: its start waits on {why}, and precip follows simulation time only"
                        )),
                    }
                }
            }
        }
    }
    changes.sort_by(|a, b| a.at_s.total_cmp(&b.at_s));
    let initial = match initial {
        Some(w) => w,
        None if !changes.is_empty() => {
            let first = changes.remove(0);
            if first.at_s > 0.0 {
                notes.push(format!(
                    "no environment in the Init: the first one ({}, at {} s) holds from the start",
                    first.event, first.at_s
                ));
            }
            first.weather
        }
        None => {
            // No storyboard weather: the first Environment anywhere (a fragment, a
            // catalog of its own).
            let environment = root
                .descendants()
                .find(|n| n.has_tag_name("Environment") && child(*n, "Weather").is_some())
                .ok_or_else(|| ScenarioError::NoWeather {
                    file: file.to_path_buf(),
                })?;
            let own = Parameters::declared_in(environment, &parameters).map_err(parameter_error)?;
            environment_weather(environment, &own, file)?
        }
    };
    Ok(Scenario {
        initial,
        changes,
        notes,
    })
}

/// When `trigger` fires, s of simulation time (no trigger: at once), or what it
/// waits on instead.
fn trigger_time(trigger: Option<Node<'_, '_>>, scope: &Parameters) -> Result<f64, String> {
    let Some(trigger) = trigger else {
        return Ok(0.0);
    };
    let mut earliest: Option<f64> = None;
    let mut waits = Vec::new();
    let mut groups = 0;
    for group in children(trigger, "ConditionGroup") {
        groups += 1;
        let mut latest = 0.0f64;
        let mut followed = true;
        for condition in children(group, "Condition") {
            match condition_time(condition, scope) {
                Ok(t) => latest = latest.max(t),
                Err(why) => {
                    waits.push(why);
                    followed = false;
                }
            }
        }
        if followed {
            earliest = Some(earliest.map_or(latest, |e| e.min(latest)));
        }
    }
    match earliest {
        Some(t) => Ok(t),
        None if groups == 0 => Ok(0.0),
        None => Err(waits.join(" or ")),
    }
}

/// When one `Condition` becomes true, or what it waits on.
fn condition_time(condition: Node<'_, '_>, scope: &Parameters) -> Result<f64, String> {
    let number = |raw: Option<&str>, what: &str| -> Result<f64, String> {
        let Some(raw) = raw else {
            return Ok(0.0);
        };
        let v = scope.resolve(raw)?;
        v.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("a {what} {v:?} that is not a number"))
    };
    let delay = number(condition.attribute("delay"), "delay")?.max(0.0);
    let Some(time) = condition
        .descendants()
        .find(|n| n.has_tag_name("SimulationTimeCondition"))
    else {
        // Name what it waits on: ByEntityCondition/ReachPositionCondition, …
        let mut path = Vec::new();
        let mut node = condition.first_element_child();
        while let Some(n) = node {
            let tag = n.tag_name().name();
            if tag != "EntityCondition" && tag != "TriggeringEntities" {
                path.push(tag.to_owned());
            }
            node = n
                .children()
                .filter(Node::is_element)
                .find(|c| !c.has_tag_name("TriggeringEntities"));
            if path.len() >= 2 {
                break;
            }
        }
        return Err(if path.is_empty() {
            "an empty condition".to_owned()
        } else {
            path.join("/")
        });
    };
    let value = number(time.attribute("value"), "SimulationTimeCondition value")?;
    let from = match time.attribute("rule").unwrap_or("greaterThan") {
        "greaterThan" | "greaterOrEqual" | "equalTo" => value.max(0.0),
        _ => 0.0,
    };
    Ok(from + delay)
}
