//! Paper items: the tables and figures of published papers as data, run with the sweep
//! machinery and compared number by number with what was published.
//!
//! An item is one TOML file `<dir>/<paper>/<name>.toml` (its id is `<paper>-<name>`); the
//! paper's directory also holds `paper.toml` with the paper's reference. An item holds
//!
//! - `kind` (`table` or `figure`), `title`, `citation` (where in the paper), `notes`;
//! - `[scene]`: the paper's protocol as a scene (the keys of `scenes/*.toml`); with a
//!   `[scene.sweep]` table the item is a sweep (critical step sizes, efficiency), without one
//!   it runs the (scheme, dt) points its published rows name;
//! - `[quick]`: scene keys replacing the protocol's for `--quick` (merged table by table);
//! - `panels`: for a figure without a scene, the ids of the items whose runs it draws;
//! - `[plot]`: for a figure, what it draws (see [`figure`]);
//! - `[[published]]`: rows as printed, each with `scheme`, optionally `dt`, and quantities as
//!   strings exactly as printed (`"0.050"`, `"100.0%"`, `"-"` for no number, `"blow-up"` where
//!   the paper says the scheme fails); the printed digits give the published uncertainty;
//! - `not_compared`: quantities that are published but not comparable (e.g. CPU times of the
//!   paper's machine), each with its reason in `notes`;
//! - `[published_grid]`: quantity to the factor between successive steps of the paper's grid,
//!   where the paper prints the largest step it tested below its threshold (a critical step
//!   "beyond which" the error exceeds 10 %): the crossing it saw lies between that step and
//!   the next; the reason in `notes`.
//!
//! An item without `[scene]` and `panels` (a table of coefficients, a figure that is not a
//! DPD simulation) is listed with its notes and not run.

pub mod compare;
pub mod figure;
pub mod item;
pub mod measure;
pub mod printed;
pub mod quantity;

pub use item::{load_all, Item, ItemError, Kind, PlotKind, PlotSpec, PublishedRow};
pub use printed::{parse_printed, Printed};
