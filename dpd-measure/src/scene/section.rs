//! How a scene file's keys reach its sections: every section takes the keys it declares out of
//! the parsed table, and what no section took is an unknown key, reported with the nearest
//! known one. The keys a section declares are the field names of its derived `Deserialize`
//! (read by `serde_aux`'s introspection), so a new field is a new key with nothing else to
//! list; serde's `flatten` cannot do this, since it does not combine with
//! `deny_unknown_fields`.

use serde::de::DeserializeOwned;
use serde_aux::serde_introspection::serde_introspect;

/// A scene file's keys as parsed; sections take theirs out of it.
pub type Keys = toml::Table;

/// Take `S`'s keys out of `keys` and read them (missing keys take `S`'s defaults). The error
/// names the key: "invalid type: string "x", expected f64 in `gamma`".
pub fn take<S: DeserializeOwned>(keys: &mut Keys) -> Result<S, String> {
    let own: Keys = serde_introspect::<S>()
        .iter()
        .filter_map(|k| Some((k.to_string(), keys.remove(*k)?)))
        .collect();
    S::deserialize(toml::Value::Table(own)).map_err(|e| one_line(&e.to_string()))
}

/// Take the table `key` out of `keys` as a `T` (`None` when absent).
pub fn take_table<T: DeserializeOwned>(keys: &mut Keys, key: &str) -> Result<Option<T>, String> {
    keys.remove(key)
        .map(|value| {
            T::deserialize(value).map_err(|e| format!("{} in `{key}`", one_line(&e.to_string())))
        })
        .transpose()
}

/// The keys `S` takes.
pub fn names<S: DeserializeOwned>() -> &'static [&'static str] {
    serde_introspect::<S>()
}

/// The error for the first key left in `keys` (none of the `known` ones), suggesting the
/// closest known key, or listing them all when none is close.
pub fn unknown(keys: &Keys, known: &[&str]) -> Option<String> {
    let key = keys.keys().next()?;
    let closest = known
        .iter()
        .map(|k| (strsim::levenshtein(key, k), *k))
        .min()
        .filter(|&(d, _)| d <= (key.chars().count() / 3).max(2));
    Some(match closest {
        Some((_, k)) => format!("unknown field `{key}`; did you mean `{k}`?"),
        None => {
            let mut all = known.to_vec();
            all.sort_unstable();
            format!(
                "unknown field `{key}`; the scene keys are {}",
                all.join(", ")
            )
        }
    })
}

/// Merge `over` into `base`: tables key by key, everything else replaced.
pub fn merge(base: &mut Keys, over: &Keys) {
    for (key, value) in over {
        match (base.get_mut(key), value) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge(b, o),
            _ => {
                base.insert(key.clone(), value.clone());
            }
        }
    }
}

/// The keys of a scene written as JSON (a results file's `scene`), where a key that was not
/// set is null: the nulls are dropped, at every depth.
pub fn json_keys(scene: serde_json::Value) -> Result<Keys, String> {
    fn without_nulls(v: serde_json::Value) -> serde_json::Value {
        match v {
            serde_json::Value::Object(map) => map
                .into_iter()
                .filter(|(_, v)| !v.is_null())
                .map(|(k, v)| (k, without_nulls(v)))
                .collect(),
            serde_json::Value::Array(items) => items.into_iter().map(without_nulls).collect(),
            other => other,
        }
    }
    Keys::try_from(without_nulls(scene)).map_err(|e| e.to_string())
}

/// toml's multi-line messages ("...\nin `gamma`\n") on one line.
fn one_line(message: &str) -> String {
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Default, Deserialize)]
    #[serde(default, deny_unknown_fields)]
    struct Part {
        gamma: f64,
        #[serde(rename = "box")]
        box_lengths: Option<[f64; 3]>,
    }

    fn keys(text: &str) -> Keys {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn a_section_takes_its_keys_and_leaves_the_others() {
        let mut k = keys("gamma = 4\nbox = [1.0, 2.0, 3.0]\nn = 3");
        let p: Part = take(&mut k).unwrap();
        assert_eq!((p.gamma, p.box_lengths), (4.0, Some([1.0, 2.0, 3.0])));
        assert_eq!(k, keys("n = 3"));
        assert_eq!(names::<Part>(), ["gamma", "box"]);
        let e = take::<Part>(&mut keys("gamma = \"x\"")).unwrap_err();
        assert!(
            e.contains("expected f64") && e.ends_with("in `gamma`"),
            "{e}"
        );
    }

    #[test]
    fn an_unknown_key_is_named_with_the_closest_known_one() {
        let known = ["gamma", "density", "box"];
        let e = unknown(&keys("gama = 1"), &known).unwrap();
        assert_eq!(e, "unknown field `gama`; did you mean `gamma`?");
        let e = unknown(&keys("temperature = 1"), &known).unwrap();
        assert!(e.ends_with("the scene keys are box, density, gamma"), "{e}");
        assert_eq!(unknown(&Keys::new(), &known), None);
    }

    #[test]
    fn tables_merge_key_by_key() {
        let mut base = keys("time = 1000.0\n[sweep]\ndt_min = 0.01\ndt_max = 0.2");
        merge(&mut base, &keys("time = 40.0\n[sweep]\ndt_min = 0.03"));
        assert_eq!(base["time"].as_float(), Some(40.0));
        assert_eq!(base["sweep"]["dt_min"].as_float(), Some(0.03));
        assert_eq!(base["sweep"]["dt_max"].as_float(), Some(0.2));
    }
}
