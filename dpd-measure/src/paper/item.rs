//! Items: a table or a figure of a paper as data, read from its file and checked.

use super::printed::parse_printed;
use super::quantity::{is_quantity, QUANTITIES, STEPS};
use crate::scene::section::merge;
use crate::scene::{Scene, SceneError};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// A table or a figure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    Table,
    Figure,
}

/// What a figure draws.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlotSpec {
    pub kind: PlotKind,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlotKind {
    /// Per panel (a sweep): relative errors of T_C (or the sweep's observable), T_K, U and P
    /// against dt on log-log axes, and g(r) per scheme where the scene has `[rdf]`.
    Errors,
    /// g(r) of every (scheme, dt) of the runs, averaged over seeds.
    Rdf,
    /// The slab profiles (x-velocity, density, temperature) of every (scheme, dt), the first
    /// seed's.
    Profile,
}

/// One row of a published table: the scheme, the time step where the row has one, and the
/// printed values by quantity.
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct PublishedRow {
    /// Registry name or scheme string of our implementation of the paper's method.
    pub scheme: String,
    /// The paper's name of the method, for the printout (default: `scheme`).
    #[serde(default)]
    pub method: Option<String>,
    #[serde(default)]
    pub dt: Option<f64>,
    /// Quantity name to the value as printed.
    #[serde(flatten)]
    pub values: BTreeMap<String, String>,
}

/// The data of one item, as read from its file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ItemFile {
    kind: Kind,
    title: String,
    citation: String,
    #[serde(default)]
    notes: String,
    #[serde(default)]
    scene: Option<toml::Table>,
    #[serde(default)]
    quick: toml::Table,
    #[serde(default)]
    panels: Vec<String>,
    #[serde(default)]
    plot: Option<PlotSpec>,
    #[serde(default)]
    not_compared: Vec<String>,
    #[serde(default)]
    published_grid: BTreeMap<String, f64>,
    #[serde(default)]
    published: Vec<PublishedRow>,
}

/// A paper's `paper.toml`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PaperFile {
    reference: String,
}

/// One table or figure of a paper.
#[derive(Clone, Debug)]
pub struct Item {
    /// `<paper>-<name>`, from the file's directory and stem.
    pub id: String,
    pub path: PathBuf,
    /// The paper's reference, from `paper.toml`.
    pub reference: String,
    pub kind: Kind,
    pub title: String,
    pub citation: String,
    pub notes: String,
    scene: Option<toml::Table>,
    quick: toml::Table,
    /// Ids of the items whose runs a figure draws.
    pub panels: Vec<String>,
    pub plot: Option<PlotSpec>,
    pub not_compared: Vec<String>,
    /// Factor between the steps of the paper's grid, for quantities it prints as the largest
    /// grid step below a threshold (see [`Printed::as_grid_step_below`]).
    pub published_grid: BTreeMap<String, f64>,
    pub published: Vec<PublishedRow>,
}

/// An item file or directory that cannot be read, or an item that is not valid.
#[derive(Debug, Error)]
pub enum ItemError {
    #[error("{path}: {message}")]
    File { path: String, message: String },
    #[error("{path}: {source}")]
    Scene {
        path: String,
        #[source]
        source: SceneError,
    },
}

fn file_error(path: &Path, message: impl ToString) -> ItemError {
    ItemError::File {
        path: path.display().to_string(),
        message: message.to_string(),
    }
}

fn read(path: &Path) -> Result<String, ItemError> {
    std::fs::read_to_string(path).map_err(|e| file_error(path, e))
}

/// Every item under `dir` (one directory per paper), sorted by id; every item's scenes are
/// resolved once to find invalid ones before anything runs.
pub fn load_all(dir: &Path) -> Result<Vec<Item>, ItemError> {
    let mut items = Vec::new();
    let papers = std::fs::read_dir(dir).map_err(|e| file_error(dir, e))?;
    for paper in papers {
        let paper = paper.map_err(|e| file_error(dir, e))?.path();
        if !paper.is_dir() {
            continue;
        }
        let reference_path = paper.join("paper.toml");
        let reference: PaperFile =
            toml::from_str(&read(&reference_path)?).map_err(|e| file_error(&reference_path, e))?;
        let files = std::fs::read_dir(&paper).map_err(|e| file_error(&paper, e))?;
        for file in files {
            let path = file.map_err(|e| file_error(&paper, e))?.path();
            let is_item = path.extension().is_some_and(|e| e == "toml") && path != reference_path;
            if is_item {
                items.push(Item::load(&path, &reference.reference)?);
            }
        }
    }
    items.sort_by(|a, b| a.id.cmp(&b.id));
    for item in &items {
        for panel in &item.panels {
            if !items.iter().any(|i| &i.id == panel && i.scene.is_some()) {
                return Err(file_error(
                    &item.path,
                    format!("panels: {panel:?} is not the id of an item with a [scene]"),
                ));
            }
        }
    }
    Ok(items)
}

impl Item {
    /// Read one item file; `reference` is its paper's.
    pub fn load(path: &Path, reference: &str) -> Result<Item, ItemError> {
        let f: ItemFile = toml::from_str(&read(path)?).map_err(|e| file_error(path, e))?;
        let stem = path.file_stem().map(|s| s.to_string_lossy().to_string());
        let paper = path
            .parent()
            .and_then(|p| p.file_name())
            .map(|s| s.to_string_lossy().to_string());
        let item = Item {
            id: format!("{}-{}", paper.unwrap_or_default(), stem.unwrap_or_default()),
            path: path.to_path_buf(),
            reference: reference.to_string(),
            kind: f.kind,
            title: f.title,
            citation: f.citation,
            notes: f.notes,
            scene: f.scene,
            quick: f.quick,
            panels: f.panels,
            plot: f.plot,
            not_compared: f.not_compared,
            published_grid: f.published_grid,
            published: f.published,
        };
        item.validate()?;
        Ok(item)
    }

    fn validate(&self) -> Result<(), ItemError> {
        for quick in [false, true] {
            self.scene(quick)?;
        }
        for row in &self.published {
            for (quantity, text) in &row.values {
                parse_printed(text).map_err(|e| {
                    file_error(&self.path, format!("published {quantity} = {text:?}: {e}"))
                })?;
                if !self.not_compared.contains(quantity) && !is_quantity(quantity) {
                    return Err(file_error(
                        &self.path,
                        format!(
                            "published quantity {quantity:?} is not measured; valid: {}, or \
                             list it in not_compared",
                            QUANTITIES.join(", ")
                        ),
                    ));
                }
            }
        }
        for (quantity, &factor) in &self.published_grid {
            if !STEPS.contains(&quantity.as_str()) {
                return Err(file_error(
                    &self.path,
                    format!(
                        "published_grid {quantity:?} is not a measured time step; valid: {}",
                        STEPS.join(", ")
                    ),
                ));
            }
            if !(factor > 1.0 && factor <= 10.0) {
                return Err(file_error(
                    &self.path,
                    format!(
                        "published_grid {quantity} = {factor}: the factor between grid steps \
                         is a number in (1, 10], e.g. 1.15 for steps 15 % apart"
                    ),
                ));
            }
        }
        if self.kind == Kind::Figure && self.runs() && self.plot.is_none() {
            return Err(file_error(&self.path, "a figure that runs needs a [plot]"));
        }
        Ok(())
    }

    /// Whether the item runs simulations (its own scene or other items' runs).
    pub fn runs(&self) -> bool {
        self.scene.is_some() || !self.panels.is_empty()
    }

    /// The item's scene (the full protocol, or with `[quick]` merged over it), validated;
    /// `None` for an item without a scene.
    pub fn scene(&self, quick: bool) -> Result<Option<Scene>, ItemError> {
        let Some(scene) = &self.scene else {
            return Ok(None);
        };
        let mut table = scene.clone();
        if quick {
            merge(&mut table, &self.quick);
        }
        let path = format!(
            "{}{}",
            self.path.display(),
            if quick {
                " (scene with [quick])"
            } else {
                " [scene]"
            }
        );
        let error = |source: SceneError| ItemError::Scene {
            path: self.path.display().to_string(),
            source,
        };
        let scene = Scene::from_keys(table, &path).map_err(error)?;
        scene.validate().map_err(|e| error(e.into()))?;
        Ok(Some(scene))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every table and figure of the four papers of docs/papers.md (counted in their texts:
    /// 000 Tables 1-4, Figures 1-5; 001 Tables 1-2, Figures 1-6; 002 Tables 1-4, Figures 1-6;
    /// 003 Tables 1-6, Figures 1-5) is an item, and every item loads and is valid.
    #[test]
    fn every_table_and_figure_of_the_four_papers_is_an_item() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/papers");
        let items = load_all(&dir).unwrap();
        let mut expected = Vec::new();
        for (paper, tables, figures) in [("000", 4, 5), ("001", 2, 6), ("002", 4, 6), ("003", 6, 5)]
        {
            expected.extend((1..=figures).map(|k| format!("{paper}-figure-{k}")));
            expected.extend((1..=tables).map(|k| format!("{paper}-table-{k}")));
        }
        expected.sort();
        let ids: Vec<&str> = items.iter().map(|i| i.id.as_str()).collect();
        assert_eq!(ids, expected);
        for item in &items {
            let table = item.id.contains("-table-");
            assert_eq!(item.kind == Kind::Table, table, "{}", item.id);
        }
    }

    /// The load error of an item whose one published row is `scheme = "vv"` and `row`.
    fn load_error(row: &str) -> String {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.toml");
        let text = format!(
            "kind = \"table\"\ntitle = \"t\"\ncitation = \"c\"\n[[published]]\n\
             scheme = \"vv\"\n{row}\n"
        );
        std::fs::write(&path, text).unwrap();
        Item::load(&path, "r").unwrap_err().to_string()
    }

    #[test]
    fn a_published_grid_is_checked_by_name_and_range() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.toml");
        let item = |grid: &str| {
            let text = format!(
                "kind = \"table\"\ntitle = \"t\"\ncitation = \"c\"\n\
                 [published_grid]\n{grid}\n"
            );
            std::fs::write(&path, text).unwrap();
            Item::load(&path, "r")
        };
        let ok = item("critical_dt_10 = 1.15").unwrap();
        assert_eq!(ok.published_grid["critical_dt_10"], 1.15);
        for key in ["critical_dt", "efficiency"] {
            let e = item(&format!("{key} = 1.15")).unwrap_err().to_string();
            assert!(e.contains(key) && e.contains("stability_dt"), "{e}");
        }
        let e = item("critical_dt_10 = 0.15").unwrap_err().to_string();
        assert!(
            e.contains("critical_dt_10 = 0.15") && e.contains("(1, 10]"),
            "{e}"
        );
    }

    #[test]
    fn a_published_quantity_we_do_not_measure_is_refused_by_name() {
        let e = load_error("critical_dt = \"0.05\"");
        assert!(
            e.contains("critical_dt") && e.contains("critical_dt_10"),
            "{e}"
        );
        let e = load_error("critical_dt_10 = \"0,05\"");
        assert!(e.contains("not a printed number"), "{e}");
    }
}
