//! The ParaView series and the page written from a real run read back: the pieces hold the
//! shape bit for bit, the collection lists them with their times, a rollback rewrites the tail,
//! and the page embeds the data and the viewer without ending its script elements early.

use hybeam::scene::Scene;
use hybeam::simulator::AnySimulator;
use hybeam_view::{read, Look, Recorder, Series};
use std::path::PathBuf;

fn scene(name: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{name}.toml"));
    Scene::from_toml(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hybeam-view-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn pieces_read_back_bit_for_bit() {
    for name in ["case1", "case1_3d", "strip_3d"] {
        let sc = scene(name);
        let radii = Look::of(&sc);
        let mut sim = AnySimulator::new(sc).unwrap();
        let dir = tmp(name);
        let mut series = Series::create(&dir, "beam", radii.clone()).unwrap();
        let mut shapes = Vec::new();
        for k in 0..4 {
            let t = k as f64 * 5e-3;
            if k > 0 {
                sim.advance(t).unwrap();
            }
            let shape = sim.shape(4);
            series.write(t, &shape).unwrap();
            shapes.push((t, shape));
        }
        // a rollback to 10 ms: the pieces from there on are replaced
        let redo = shapes[2].1.clone();
        series.write(0.01, &redo).unwrap();
        assert_eq!(series.len(), 3, "{name}");
        let pvd = series.finish().unwrap();
        drop(series);
        let pieces = read::read_series(&pvd).unwrap();
        assert_eq!(pieces.len(), 3, "{name}");
        for (p, (t, shape)) in pieces.iter().zip(&shapes) {
            assert_eq!(p.time, *t, "{name}");
            assert_eq!(&p.shape, shape, "{name} at {t}");
            for (q, r) in p.shape.points.iter().zip(&p.radius) {
                assert_eq!(*r, radii.radii[q.segment][0], "{name}");
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
fn page_embeds_data_and_viewer() {
    let sc = scene("case1");
    let radii = Look::of(&sc);
    let mut sim = AnySimulator::new(sc.clone()).unwrap();
    let mut rec = Recorder::new(
        "case1 </script> & <b>",
        &sc.gravity,
        radii,
        vec!["tip.position.y".into()],
    );
    for k in 0..5 {
        let t = k as f64 * 1e-2;
        if k > 0 {
            sim.advance(t).unwrap();
        }
        rec.push(t, &sim.shape(4), &[sim.outputs().tip_position()[1]]);
    }
    // a reset to 0: the recording starts over
    rec.push(0.0, &sim.shape(4), &[0.0]);
    assert_eq!(rec.len(), 1);
    let page = rec.page();
    // exactly the template's script elements: the data and the viewer
    assert_eq!(page.matches("</script>").count(), 2);
    assert!(page.contains("case1 &lt;/script&gt; &amp; &lt;b&gt;"));
    let data_start = page
        .find("id=\"hybeam-data\" type=\"application/json\">")
        .unwrap();
    let json_start = page[data_start..].find('>').unwrap() + data_start + 1;
    let json_end = page[json_start..].find("</script>").unwrap() + json_start;
    let json: serde_json::Value =
        serde_json::from_str(&page[json_start..json_end].replace("<\\/", "</")).unwrap();
    // the modal segment: 4 + 1 samples; the ANCF segment: 8 elements × 4 + 1
    assert_eq!(json["points"], (4 + 1) + (8 * 4 + 1));
    assert_eq!(json["tip"]["names"][0], "tip.position.y");
    assert_eq!(json["up"], serde_json::json!([0.0, 1.0, 0.0]));
    assert!(page.len() > 500_000, "the viewer is bundled into the page");
}

#[test]
fn a_long_recording_is_thinned_keeping_the_ends() {
    let sc = scene("case1");
    let radii = Look::of(&sc);
    let sim = AnySimulator::new(sc.clone()).unwrap();
    let shape = sim.shape(1);
    let mut rec = Recorder::new("long", &sc.gravity, radii, vec!["k".into()]);
    let n = hybeam_view::animation::MAX_FRAMES * 3 + 7;
    for k in 0..n {
        rec.push(k as f64, &shape, &[k as f64]);
    }
    assert!(
        rec.len() <= hybeam_view::animation::MAX_FRAMES,
        "{}",
        rec.len()
    );
    assert!(rec.len() > hybeam_view::animation::MAX_FRAMES / 2);
    let page = rec.page();
    let tag = "type=\"application/json\">";
    let json_start = page.find(tag).unwrap() + tag.len();
    let json_end = page[json_start..].find("</script>").unwrap() + json_start;
    let json: serde_json::Value = serde_json::from_str(&page[json_start..json_end]).unwrap();
    use base64::Engine as _;
    let times: Vec<f64> = base64::engine::general_purpose::STANDARD
        .decode(json["times"].as_str().unwrap())
        .unwrap()
        .chunks(8)
        .map(|b| f64::from_le_bytes(b.try_into().unwrap()))
        .collect();
    assert_eq!(times.len(), rec.len());
    assert_eq!(times[0], 0.0);
    assert_eq!(*times.last().unwrap(), (n - 1) as f64);
    assert!(times.windows(2).all(|w| w[1] > w[0]));
    let tips: Vec<f64> = base64::engine::general_purpose::STANDARD
        .decode(json["tip"]["values"].as_str().unwrap())
        .unwrap()
        .chunks(8)
        .map(|b| f64::from_le_bytes(b.try_into().unwrap()))
        .collect();
    assert_eq!(tips, times, "each kept frame keeps its own tip value");
}

/// A tapered tube and attached masses, as written: the radius at each point is the section's
/// outer radius d(s)/2 at its arc length (the taper's closed form), and each mass is a vertex
/// at its centre (the straight start: root + (s₀ + at)·x + the offset in section axes) with its
/// sphere's radius, read back by `read_dressed`.
#[test]
fn tapers_and_masses_are_drawn_where_they_are() {
    let text = r#"name = "dressed"
gravity = [0.0, -9.81]
[[segments]]
name = "root"
kind = "modal"
length = 0.5
section = "round"
diameter = 0.02
youngs_modulus = 2.1e11
density = 7850.0
modes = 2
[[segments]]
name = "arm"
kind = "ancf"
length = 1.0
section = "tube"
diameter = [0.02, 0.01]
inner_diameter = [0.016, 0.008]
youngs_modulus = 2.1e11
density = 7850.0
elements = 4
[[masses]]
name = "lamp"
segment = "root"
at = 0.3
mass = 1.2
offset = [0.0, 0.05]
[[masses]]
name = "nozzle"
segment = "arm"
at = 0.6
mass = 0.4
"#;
    let sc = hybeam::scene::Scene::from_toml(text).unwrap();
    let look = Look::of(&sc);
    let sim = AnySimulator::new(sc).unwrap();
    let dir = tmp("dressed");
    let mut series = Series::create(&dir, "beam", look.clone()).unwrap();
    series.write(0.0, &sim.shape(4)).unwrap();
    let pvd = series.finish().unwrap();
    drop(series);
    let piece = read::read_series(&pvd).unwrap().remove(0);
    for (q, r) in piece.shape.points.iter().zip(&piece.radius) {
        let want = if q.segment == 0 {
            0.01
        } else {
            0.5 * (0.02 + (q.arc - 0.5) * (0.01 - 0.02))
        };
        assert!((r - want).abs() <= 1e-15, "at {}: {r} vs {want}", q.arc);
    }
    let sphere = |m: f64| (3.0 * m / (4.0 * std::f64::consts::PI * 2000.0)).cbrt();
    let want = [
        ([0.3, 0.05, 0.0], sphere(1.2)),
        ([1.1, 0.0, 0.0], sphere(0.4)),
    ];
    assert_eq!(piece.masses.len(), 2);
    for ((c, r), (wc, wr)) in piece.masses.iter().zip(want) {
        for k in 0..3 {
            assert!((c[k] - wc[k]).abs() <= 1e-12, "{c:?} vs {wc:?}");
        }
        assert!((r - wr).abs() <= 1e-15);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
