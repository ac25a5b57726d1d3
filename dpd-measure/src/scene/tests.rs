use super::*;

fn error_of(text: &str) -> String {
    match Scene::from_toml(text, "t.toml").and_then(|s| Ok(s.validate()?)) {
        Ok(()) => panic!("{text:?} was accepted"),
        Err(e) => e.to_string(),
    }
}

fn keys(text: &str) -> Keys {
    toml::from_str(text).unwrap()
}

#[test]
fn a_scene_names_only_what_it_needs() {
    let s = Scene::from_toml("gamma = 40.5\n[rdf]\nbins = 20\n", "t").unwrap();
    assert_eq!(
        (s.physics.gamma, s.geometry.n, s.observe.rdf.unwrap().bins),
        (40.5, 500, 20)
    );
    assert!(s.observe.vacf.is_none() && s.sweep.is_none());
}

#[test]
fn g_of_r_is_sampled_every_interval_in_whole_samples() {
    let s = Scene::from_toml("[rdf]\ninterval = 0.5\n", "t").unwrap();
    // Samples every 0.1 / 0.05 = 2 steps; 0.5 / 0.1 = 5 samples per g(r) record.
    assert_eq!((s.run.sample_every(0.05), s.rdf_stride(0.05)), (2, 5));
    // At dt = 0.3 every step is a sample (0.3 time units apart): 0.5 / 0.3 rounds to 2.
    assert_eq!((s.run.sample_every(0.3), s.rdf_stride(0.3)), (1, 2));
    // An interval shorter than the sampling records every sample.
    assert_eq!(s.rdf_stride(2.0), 1);
    assert_eq!(
        Scene::from_toml("[rdf]\n", "t").unwrap().rdf_stride(0.05),
        1
    );
}

#[test]
fn unknown_keys_and_invalid_values_name_the_key() {
    for (text, key) in [
        ("gama = 4.5", "did you mean `gamma`"),
        ("[sweep]\ndt_mni = 0.1", "dt_mni"),
        ("[rdf]\nbinz = 3", "binz"),
        ("gamma = -1.0", "gamma"),
        ("gamma = \"x\"", "in `gamma`"),
        ("[rdf]\nbins = 2.5", "rdf.bins"),
        ("kbt = 0.0", "kbt"),
        ("n = 10", "n"),
        ("skin = -0.1", "skin"),
        ("skin = 1.5", "skin"),
        // Edge 2.37: enough for the default skin 0 (2 r_c), not for 0.5 (2 (r_c + skin)).
        ("n = 40\nskin = 0.5", "n"),
        ("average_fraction = 1.5", "average_fraction"),
        ("runs = 0", "runs"),
        ("[rdf]\nr_max = 9.0", "rdf.r_max"),
        ("[rdf]\ninterval = 0.0", "rdf.interval"),
        ("[sweep]\ndt_factor = 1.0", "sweep.dt_factor"),
        ("[sweep]\ndt_min = 0.1\ndt_max = 0.01", "sweep.dt_max"),
        ("[sweep]\nreference = \"abo\"", "sweep.reference"),
        (
            "[trajectory]\nfile = \"t.gsd\"\nevery = 0.0",
            "trajectory.every",
        ),
    ] {
        let e = error_of(text);
        assert!(e.contains(key), "{text:?}: {e}");
    }
}

#[test]
fn every_key_of_every_section_is_known_and_written_back() {
    let text = "description = \"d\"\nscheme = \"vv\"\ndt = 0.02\ntime = 3.0\n\
                average_fraction = 0.5\nsample_interval = 0.2\nseed = 4\nruns = 2\nthreads = 1\n\
                a = 20.0\ngamma = 40.5\nkbt = 1.5\nmass = 2.0\nweight_exponent = 1.0\n\
                shear_rate = 0.1\nn = 300\ndensity = 4.0\nskin = 0.2\nenergy_balance = true\n\
                [rdf]\nr_max = 2.0\nbins = 20\n[vacf]\nmax_lag = 1.0\n[profile]\nbins = 4\n\
                [sweep]\nschemes = [\"vv\"]\n[trajectory]\nfile = \"t.gsd\"\nevery = 1.0\n";
    let scene = Scene::from_toml(text, "t").unwrap();
    scene.validate().unwrap();
    let again = Scene::from_toml(&scene.to_toml(), "again").unwrap();
    assert_eq!(again, scene);
    assert_eq!(
        (scene.run.dt, scene.physics.kbt, scene.geometry.skin),
        (0.02, 1.5, 0.2)
    );
}

#[test]
fn the_default_skin_allows_a_box_of_edge_two_r_c() {
    let scene = Scene::from_toml("n = 40", "t.toml").unwrap();
    assert_eq!(scene.geometry.skin, 0.0);
    scene.validate().unwrap();
}

#[test]
fn keys_given_by_a_caller_replace_the_scene_file_s() {
    let s = Scene::resolve(None, &keys("gamma = 450.0\nn = 100")).unwrap();
    assert_eq!(
        (s.physics.gamma, s.geometry.n, s.geometry.density),
        (450.0, 100, 3.0)
    );
    let e = Scene::resolve(None, &keys("dt = nan")).unwrap_err();
    assert!(e.to_string().contains("dt"), "{e}");
    let e = Scene::resolve(None, &keys("denisty = 3.0")).unwrap_err();
    assert!(e.to_string().contains("did you mean `density`"), "{e}");
}

#[test]
fn sweep_keys_merge_into_the_scene_s_table_and_are_validated() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("s.toml");
    std::fs::write(&file, "[sweep]\ndt_max = 0.1\n").unwrap();
    let over = keys("[sweep]\nschemes = [\"aboba\", \"vv\"]\ndt_min = 0.05");
    let w = Scene::resolve(Some(&file), &over).unwrap().sweep.unwrap();
    assert_eq!((w.schemes.len(), w.dt_min, w.dt_max), (2, 0.05, 0.1));
    assert_eq!(w.reference.as_deref(), Some("vv"));
    let bad = keys("[sweep]\nreference = \"baoab\"");
    let e = Scene::resolve(Some(&file), &bad).unwrap_err().to_string();
    assert!(
        e.starts_with("scene: invalid sweep.reference = baoab"),
        "{e}"
    );
}

#[test]
fn every_shipped_scene_is_valid() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            // scenes/papers/: paper items, checked by the paper module's tests.
            continue;
        }
        Scene::load(&path).unwrap().validate().unwrap();
        count += 1;
    }
    assert!(count >= 6);
}
