//! The assembled Newton matrix (mass, damping, stiffness, joint rows and their λ-Hessian, tip
//! load and moment) against central differences of the assembled residual, at a random deformed state.

mod common;
use common::*;
use hybeam::model::{Model, Planar};

fn check(header: &str, segs: &[String]) {
    let s = scene(header, segs);
    let mut model = Model::<Planar>::from_scene(&s).unwrap();
    model.set_tip_force([0.3, -0.7]);
    model.set_tip_moment(0.2);
    check_newton_matrix(&mut model);
}

#[test]
fn pinned_modal_root_with_ancf_and_modal_tip() {
    let d = 0.004;
    check(
        "root = \"pinned\"\ngravity = [1.0, -9.81]",
        &[
            modal("m1", 0.2, &round(d), 3, true, "damping_ratio = 0.05"),
            ancf("a", 0.2, &round(d), 2, "damping_time = 1e-3"),
            modal("m2", 0.2, &round(d), 2, false, ""),
        ],
    );
}

#[test]
fn clamped_ancf_root_with_modal_middle() {
    let d = 0.004;
    check(
        "gravity = [0.0, -9.81]",
        &[
            ancf("a1", 0.2, &round(d), 2, "strain = \"paper\""),
            modal("m", 0.2, &round(d), 2, true, "damping_time = 1e-3"),
            modal("m2", 0.1, &round(d), 2, false, ""),
            ancf("a2", 0.2, &round(d), 2, ""),
        ],
    );
}

#[test]
fn spatial_ancf_with_twist_director_and_its_inertia() {
    // a soft, thick rod, so that the director inertia (ρI_p = 4.8e-3 kg m: mass entries ~6e-4,
    // velocity terms ~1e-4) stands far above the tolerance 1e-6 + 1e-8·max|residual| (~1e-7)
    use hybeam::model::Spatial;
    for extra in ["", "damping_time = 1e-3"] {
        let seg = format!(
            "name = \"a\"\nkind = \"ancf\"\nlength = 0.4\n{}\nyoungs_modulus = 1e4\ndensity = 7850.0\nelements = 3\n{extra}\n",
            round(0.05)
        );
        let s = scene(
            "space = \"spatial\"\ntorsion = true\ngravity = [0.0, 1.0, -9.81]",
            &[seg],
        );
        let mut model = Model::<Spatial>::from_scene(&s).unwrap();
        model.set_tip_force([0.3, -0.7, 0.2]);
        let worst = check_newton_matrix(&mut model);
        eprintln!("{extra:?}: worst error {worst:.2e} of the tolerance");
    }
}

#[test]
fn spatial_modal_root_with_ancf_tip_nonlinear_and_linear() {
    // the spatial modal body (its nonlinear foreshortening and curvature terms, or the linear
    // frame) with the tip port's directors into an ANCF segment with twist, a modal tip segment
    // (free frame) after it; unequal bending stiffnesses (rectangle) tell the planes apart
    use hybeam::model::Spatial;
    let rect = "section = \"rectangle\"\nwidth = 4e-3\nheight = 6e-3";
    for lin in ["", "linear = true"] {
        let s = scene(
            "space = \"spatial\"\ntorsion = true\ngravity = [0.0, 1.0, -9.81]",
            &[
                modal(
                    "m1",
                    0.2,
                    rect,
                    3,
                    true,
                    &format!("damping_ratio = 0.05\n{lin}"),
                ),
                ancf("a", 0.2, rect, 2, "damping_time = 1e-3"),
                modal("m2", 0.2, rect, 2, false, lin),
            ],
        );
        let mut model = Model::<Spatial>::from_scene(&s).unwrap();
        model.set_tip_force([0.3, -0.7, 0.2]);
        let worst = check_newton_matrix(&mut model);
        eprintln!("{lin:?}: worst error {worst:.2e} of the tolerance");
    }
}
