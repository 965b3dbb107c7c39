//! OpenSCENARIO parameters: `ParameterDeclarations` give names values, an attribute
//! written `$name` takes the value, and one written `${…}` (1.2) an expression's
//! ([`super::expressions`]). A declaration may use the ones before it; a catalog
//! entry's are overridden by the reference's `ParameterAssignments`.

use std::collections::BTreeMap;

use roxmltree::Node;

use super::expressions::evaluate;

/// The parameters in scope: name → value as written (resolved).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Parameters {
    values: BTreeMap<String, String>,
}

impl Parameters {
    /// `outer` with the `ParameterDeclarations` that are children of `node` added,
    /// each resolved against those before it.
    pub fn declared_in(node: Node<'_, '_>, outer: &Self) -> Result<Self, String> {
        let mut scope = outer.clone();
        for declarations in node
            .children()
            .filter(|c| c.has_tag_name("ParameterDeclarations"))
        {
            for d in declarations
                .children()
                .filter(|c| c.has_tag_name("ParameterDeclaration"))
            {
                let name = d
                    .attribute("name")
                    .ok_or("a ParameterDeclaration without a name")?;
                let value = d.attribute("value").unwrap_or_default();
                let resolved = scope
                    .resolve(value)
                    .map_err(|e| format!("parameter {name}: {e}"))?;
                scope
                    .values
                    .insert(name.trim_start_matches('$').to_owned(), resolved);
            }
        }
        Ok(scope)
    }

    /// These parameters with the `ParameterAssignments` that are children of
    /// `reference` (each value resolved in `caller`'s scope) set; a name not
    /// declared here is an error.
    pub fn assigned_from(&self, reference: Node<'_, '_>, caller: &Self) -> Result<Self, String> {
        let mut scope = self.clone();
        for a in reference
            .descendants()
            .filter(|c| c.has_tag_name("ParameterAssignment"))
        {
            let name = a
                .attribute("parameterRef")
                .ok_or("a ParameterAssignment without parameterRef")?
                .trim_start_matches('$');
            if !scope.values.contains_key(name) {
                return Err(format!(
                    "ParameterAssignment to {name}, which the catalog entry does not declare"
                ));
            }
            let value = caller
                .resolve(a.attribute("value").unwrap_or_default())
                .map_err(|e| format!("parameter {name}: {e}"))?;
            scope.values.insert(name.to_owned(), value);
        }
        Ok(scope)
    }

    /// `raw` with a `$name` replaced by its value and `${…}` by the expression's.
    pub fn resolve(&self, raw: &str) -> Result<String, String> {
        let text = raw.trim();
        if let Some(expression) = text.strip_prefix("${").and_then(|t| t.strip_suffix('}')) {
            let v = evaluate(expression, &|name| self.number(name))?;
            return Ok(v.to_string());
        }
        match text.strip_prefix('$') {
            Some(name) => self.values.get(name).cloned().ok_or_else(|| {
                format!(
                    "${name} is not declared: add <ParameterDeclaration name=\"{name}\" … value=\"…\"/> to the ParameterDeclarations"
                )
            }),
            None => Ok(raw.to_owned()),
        }
    }

    /// A parameter's value as a number (for expressions; `true`/`false` are 1/0).
    fn number(&self, name: &str) -> Result<f64, String> {
        let v = self
            .values
            .get(name)
            .ok_or_else(|| format!("${name} is not declared"))?;
        match v.trim() {
            "true" => Ok(1.0),
            "false" => Ok(0.0),
            t => t
                .parse()
                .map_err(|_| format!("${name} = {v:?} is not a number")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn declarations_references_expressions_and_assignments() {
        let text = r#"<S>
            <ParameterDeclarations>
              <ParameterDeclaration name="FogVisualRange" parameterType="double" value="2000"/>
              <ParameterDeclaration name="Half" parameterType="double" value="${$FogVisualRange / 2}"/>
              <ParameterDeclaration name="Kind" parameterType="string" value="rain"/>
            </ParameterDeclarations>
            <Ref><ParameterAssignments>
              <ParameterAssignment parameterRef="Kind" value="$Kind"/>
            </ParameterAssignments></Ref>
          </S>"#;
        let doc = roxmltree::Document::parse(text).expect("xml");
        let root = doc.root_element();
        let p = Parameters::declared_in(root, &Parameters::default()).expect("valid");
        assert_eq!(p.resolve("$FogVisualRange").as_deref(), Ok("2000"));
        assert_eq!(p.resolve("$Half").as_deref(), Ok("1000"));
        assert_eq!(p.resolve("${$Half * 3 + 1}").as_deref(), Ok("3001"));
        assert_eq!(p.resolve("12.5").as_deref(), Ok("12.5"));
        let e = p.resolve("$Missing").expect_err("undeclared");
        assert!(e.contains("ParameterDeclaration name=\"Missing\""), "{e}");
        assert!(p.resolve("${$Kind + 1}").is_err(), "a string in arithmetic");
        // A catalog entry declaring Kind = snow, assigned the scenario's rain.
        let entry = roxmltree::Document::parse(
            r#"<E><ParameterDeclarations><ParameterDeclaration name="Kind" value="snow"/></ParameterDeclarations></E>"#,
        )
        .expect("xml");
        let own =
            Parameters::declared_in(entry.root_element(), &Parameters::default()).expect("valid");
        let reference = root
            .children()
            .find(|c| c.has_tag_name("Ref"))
            .expect("the reference");
        let assigned = own.assigned_from(reference, &p).expect("declared");
        assert_eq!(assigned.resolve("$Kind").as_deref(), Ok("rain"));
        assert!(
            Parameters::default().assigned_from(reference, &p).is_err(),
            "Kind is not the entry's"
        );
    }
}
