//! Tests of the demo page and of the cost chart's labels, on hand-made reports whose best rows
//! are known.

use super::chart::LABEL_REACH;
use super::demo_page::{
    demo_page, fair_reference, fastest_third, scene_verdict, DemoPage, DemoReport, DemoScene,
};
use super::{cost_chart_svg, ReferenceInfo, Report, TechniqueResult};
use crate::reference::ground_truth::ReferenceModel;
use crate::technique::Technique;

fn row(name: &str, mae: f64, ms: f64) -> TechniqueResult {
    TechniqueResult {
        technique: name.into(),
        mse: mae * mae,
        mae,
        psnr: -10.0 * (mae * mae).log10(),
        ssim: 0.9,
        halo_bright: 0.01,
        halo_dark: -0.0,
        settings: None,
        gpu_ms: Some(ms),
    }
}

fn report(model: &str, spp: Option<u32>, results: Vec<TechniqueResult>) -> Report {
    Report {
        scene: "s".into(),
        camera: "closeup".into(),
        scene_options: String::new(),
        width: 64,
        height: 48,
        guard_band: 8,
        reference: ReferenceInfo {
            model: model.into(),
            spp,
            radius: Some(0.5),
        },
        adapter: "llvmpipe".into(),
        software_adapter: true,
        diff_scale: 0.2,
        results,
        temporal: None,
    }
}

/// Two families as the demo scores them. The scene's six times sorted are 1, 1.2, 2, 4, 9, 10:
/// its fastest third is the two rows within 1.2 ms.
fn reports() -> [Report; 2] {
    [
        report(
            "vao",
            None,
            vec![
                row("vao", 0.05, 1.0),
                row("rt-vao", 0.01, 9.0),
                row("sd-vao", 0.03, 4.0),
            ],
        ),
        report(
            "hemisphere",
            Some(64),
            vec![
                row("hbao+", 0.06, 2.0),
                row("gtao", 0.08, 1.2),
                row("rtao", 0.02, 10.0),
            ],
        ),
    ]
}

fn scene<'a>(name: &'a str, reports: &'a [Report; 2]) -> DemoScene<'a> {
    DemoScene {
        name,
        camera: "closeup",
        reports: reports
            .iter()
            .zip(["vao", "hemisphere"])
            .map(|(report, folder)| DemoReport { folder, report })
            .collect(),
    }
}

fn page<'a>(scenes: Vec<DemoScene<'a>>) -> DemoPage<'a> {
    DemoPage {
        adapter: "llvmpipe (Vulkan)",
        settings: "64×48",
        software_adapter: true,
        diff_scale: 0.2,
        composites: true,
        scenes,
    }
}

#[test]
fn each_family_is_scored_against_its_own_model() {
    for t in Technique::all() {
        let vao = t.estimator().name() == "vao";
        let expected = if vao {
            ReferenceModel::Vao
        } else {
            ReferenceModel::Hemisphere
        };
        assert_eq!(fair_reference(t), expected, "{t}");
    }
    for (name, model) in [
        ("rt-vao", ReferenceModel::Vao),
        ("sd-vao", ReferenceModel::Vao),
        ("hbao+", ReferenceModel::Hemisphere),
        ("gtao-vb", ReferenceModel::Hemisphere),
        ("ssao", ReferenceModel::Hemisphere),
        ("rtao", ReferenceModel::Hemisphere),
    ] {
        assert_eq!(fair_reference(name.parse().unwrap()), model, "{name}");
    }
}

#[test]
fn the_verdict_names_the_lowest_mae_row_per_family_and_per_budget() {
    let reports = reports();
    let s = scene("stairs", &reports);
    assert_eq!(fastest_third(&s), Some(1.2));
    let v = scene_verdict(&s, true);
    assert!(
        v.contains("vao reference (rows whose estimator is VAO): the closest is rt-vao (MAE 0.0100, 9.0 ms (CPU));"),
        "{v}"
    );
    assert!(
        v.contains("; rtao traces rays through the scene's geometry as the reference does"),
        "{v}"
    );
    // A screen-space row that wins is not said to trace.
    let mut screen = reports.clone();
    screen[1].results[0].mae = 0.01;
    let w = scene_verdict(&scene("stairs", &screen), true);
    assert!(
        w.contains("closest is hbao+ (MAE 0.0100, 2.0 ms (CPU));") && !w.contains("hbao+ traces"),
        "{w}"
    );
    // Beside a row that traces, the best of the rows without rays: sd-vao, hbao+.
    for best in [
        "sd-vao (MAE 0.0300, 4.0 ms (CPU))",
        "hbao+ (MAE 0.0600, 2.0 ms (CPU))",
    ] {
        assert!(
            v.contains(&format!(
                "of the rows that trace none the closest is {best}."
            )),
            "{v}"
        );
    }
    // Within 1.2 ms only vao (0.05) of its family.
    assert!(
        v.contains("fastest third (≤ 1.2 ms (CPU)), vao (MAE 0.0500, 1.0 ms (CPU))"),
        "{v}"
    );
    assert!(v.contains("the closest is rtao (MAE 0.0200"), "{v}");
    // gtao (1.2 ms) is the hemisphere family's only row within the budget, though hbao+ is closer.
    assert!(v.contains("gtao (MAE 0.0800, 1.2 ms (CPU))"), "{v}");
    assert!(v.contains("do not rank GPU cost"), "{v}");
    // On a GPU: no CPU mark, and a best row that is also fast is said to be.
    let mut gpu = reports.clone();
    gpu[0].results[1].gpu_ms = Some(0.5);
    let v = scene_verdict(&scene("stairs", &gpu), false);
    assert!(
        v.contains("rt-vao (MAE 0.0100, 0.500 ms), which is also among"),
        "{v}"
    );
    assert!(!v.contains("CPU"), "{v}");
}

/// The cells of each `<tbody>` row.
fn table_rows(html: &str) -> Vec<Vec<String>> {
    let body = &html[html.find("<tbody>").unwrap()..html.find("</tbody>").unwrap()];
    body.split("<tr>")
        .skip(1)
        .map(|tr| {
            tr.split("<td")
                .skip(1)
                .map(|td| {
                    let start = td.find('>').unwrap() + 1;
                    td[start..td.find("</td>").unwrap()].to_owned()
                })
                .collect()
        })
        .collect()
}

#[test]
fn the_page_names_references_sorts_its_table_and_states_one_scale() {
    let reports = reports();
    let html = demo_page(&page(vec![
        scene("stairs", &reports),
        scene("grass", &reports),
    ]));
    let rows = table_rows(&html);
    assert_eq!(rows.len(), 12);
    for cells in &rows {
        // Columns: scene, technique, estimator, reference, MSE, MAE, …, time.
        let technique: Technique = cells[1]
            .trim_start_matches("<code>")
            .trim_end_matches("</code>")
            .parse()
            .unwrap();
        let expected = fair_reference(technique).name();
        assert!(
            cells[3].starts_with(&format!("{expected}, R = 0.5")),
            "{cells:?}"
        );
        assert!(cells[10].ends_with(" ms (CPU)"), "{cells:?}");
    }
    // Page order of scenes, then reference, then MAE.
    let keys: Vec<(usize, usize, f64)> = rows
        .iter()
        .map(|c| {
            let scene = usize::from(!c[0].contains("stairs"));
            let reference = usize::from(c[3].starts_with("hemisphere"));
            (scene, reference, c[5].parse().unwrap())
        })
        .collect();
    assert!(
        keys.windows(2).all(|w| w[0] <= w[1]),
        "not sorted: {keys:?}"
    );
    assert!(html.contains("<th>MAE</th>") && html.contains("addEventListener('click'"));
    // Self-contained: no outside file, no script loaded from anywhere.
    assert!(!html.contains("<script src") && !html.contains("http"));
    // One scale, stated with its colours.
    assert!(html.contains("uses one scale: <span>−0.2</span>"), "{html}");
    assert!(html
        .contains("linear-gradient(to right, rgb(0, 0, 255), rgb(255, 255, 255), rgb(255, 0, 0))"));
    // Every scene's verdict, in the list and above its grid; only the first grid open.
    assert_eq!(html.matches("class=\"verdict\"").count(), 2);
    assert_eq!(html.matches("<details open>").count(), 1);
    assert_eq!(html.matches("<details>").count(), 1);
    assert!(!html.contains("CPU) ms"));
    // Each row's images come from its family's folder.
    assert!(html.contains("src=\"hemisphere/gtao.diff.png\""));
    assert!(html.contains("src=\"vao/sd-vao.png\""));
    assert!(!html.contains("vao/gtao"));
}

/// A dot's (cx, cy) and the (x, y, text) of the label right after it.
type DotLabel = ((f64, f64), (f64, f64, String));

fn dots_and_labels(svg: &str) -> Vec<DotLabel> {
    let attr = |s: &str, name: &str| -> f64 {
        let i = s.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        s[i..i + s[i..].find('"').unwrap()].parse().unwrap()
    };
    svg.split("<circle")
        .skip(1)
        .map(|c| {
            let label = &c[c.find("<text class=\"label\"").unwrap()..];
            let text = &label[label.find('>').unwrap() + 1..label.find("</text>").unwrap()];
            (
                (attr(c, "cx"), attr(c, "cy")),
                (attr(label, "x"), attr(label, "y"), text.to_owned()),
            )
        })
        .collect()
}

#[test]
fn cost_labels_sit_next_to_their_dots() {
    // 30 rows in a tight cluster (as a family's screen-space rows are on lavapipe) and a few apart.
    let mut results: Vec<TechniqueResult> = (0..30)
        .map(|i| {
            let mut r = row(&format!("row-{i}"), 0.0, 1.0 + 0.01 * i as f64);
            r.mse = 1e-3 * (1.0 + 0.02 * i as f64);
            r
        })
        .collect();
    results.push(row("slow", 0.001, 40.0));
    results.push(row("fast", 0.2, 0.1));
    let svg = cost_chart_svg(&report("hemisphere", Some(64), results)).unwrap();
    let pairs = dots_and_labels(&svg);
    assert_eq!(pairs.len(), 32);
    let mut numbered = 0;
    for ((cx, cy), (x, y, text)) in &pairs {
        let d = f64::hypot(x - cx, y - cy);
        assert!(
            d <= LABEL_REACH + 1.0,
            "label {text} {d:.1} px from its dot"
        );
        if let Ok(n) = text.parse::<usize>() {
            numbered += 1;
            // A number is named in the list beside the plot.
            assert!(svg.contains(&format!(">{n} row-")), "{n} not listed");
        }
    }
    assert!(numbered > 0, "30 close dots cannot all carry their names");
    for name in ["slow", "fast"] {
        assert!(svg.contains(&format!(">{name}</text>")), "{name} not named");
    }
    // No two labels at the same place.
    for (i, a) in pairs.iter().enumerate() {
        for b in &pairs[i + 1..] {
            assert!(a.1 .0 != b.1 .0 || a.1 .1 != b.1 .1, "{a:?} {b:?}");
        }
    }
}
