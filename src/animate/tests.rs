use super::*;

fn scene() -> Scene {
    let times = vec![0.0, 0.5, 1.0];
    let poses = |dx: f64| -> Vec<Pose> {
        times
            .iter()
            .map(|&t| Pose::at([t + dx, 0.0, 0.5]))
            .collect()
    };
    Scene {
        title: "test".into(),
        note: None,
        items: vec![
            Item {
                name: "wheel".into(),
                shape: Shape::Disc {
                    radius: 0.5,
                    thickness: 0.05,
                },
                poses: poses(0.0),
            },
            Item {
                name: "board".into(),
                shape: Shape::Box {
                    size: [1.0, 0.3, 0.02],
                },
                poses: poses(1.0),
            },
        ],
        labels: vec![Label {
            name: "x".into(),
            values: times.clone(),
        }],
        traces: vec![Trace {
            name: "contact".into(),
            points: times.iter().map(|&t| [t, 0.0, 0.0]).collect(),
        }],
        times,
    }
}

fn refused(change: impl FnOnce(&mut Scene)) -> AnimateError {
    let mut scene = scene();
    change(&mut scene);
    page(&scene).expect_err("the scene is refused")
}

/// The JSON embedded in a page.
fn embedded(html: &str) -> &str {
    let open = "<script type=\"application/json\" id=\"chaplygin-data\">";
    let start = html.find(open).expect("the page embeds its data") + open.len();
    let end = start
        + html[start..]
            .find("</script>")
            .expect("the data's element is closed");
    &html[start..end]
}

/// The number tokens of a JSON text in order, parsed by Rust's correctly
/// rounded parser (serde_json's default one may be one unit in the last
/// place off).
fn number_tokens(json: &str) -> Vec<f64> {
    let mut numbers = Vec::new();
    let mut token = String::new();
    let mut in_string = false;
    let mut escaped = false;
    for c in json.chars() {
        if in_string {
            match (escaped, c) {
                (true, _) => escaped = false,
                (false, '\\') => escaped = true,
                (false, '"') => in_string = false,
                _ => {}
            }
        } else if c == '"' {
            in_string = true;
        } else if c.is_ascii_digit() || "+-.eE".contains(c) {
            token.push(c);
            continue;
        }
        if !token.is_empty() {
            numbers.push(token.parse::<f64>().expect("a JSON number"));
            token.clear();
        }
    }
    numbers
}

#[test]
fn a_valid_scene_makes_a_page() {
    let html = page(&scene()).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert!(html.contains(
        "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; \
         script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data: blob:\">"
    ));
    assert!(html.contains(THREE) && html.contains(SCRIPT) && html.contains(STYLE));
    assert!(!html.contains("{{"), "every placeholder is filled");
    assert!(html.contains("<p id=\"note\" hidden></p>"));
}

#[test]
fn no_error_for_a_single_frame_without_items() {
    let scene = Scene {
        times: vec![2.0],
        ..Scene::default()
    };
    page(&scene).unwrap();
}

#[test]
fn every_error_names_what_is_wrong() {
    assert_eq!(refused(|s| s.times.clear()), AnimateError::NoFrames);
    assert_eq!(
        refused(|s| s.times[1] = f64::NAN).to_string(),
        "frame 1: the time NaN is not a finite number"
    );
    assert_eq!(
        refused(|s| s.times[2] = 0.5),
        AnimateError::TimesNotIncreasing {
            frame: 2,
            previous: 0.5,
            value: 0.5
        }
    );
    assert_eq!(
        refused(|s| s.times[2] = 0.5).to_string(),
        "frame 2: the time 0.5 is not after frame 1's time 0.5; times must increase"
    );
    assert_eq!(
        refused(|s| s.items[1].name = "wheel".into()),
        AnimateError::DuplicateName {
            kind: "item",
            name: "wheel".into()
        }
    );
    assert_eq!(
        refused(|s| s.labels.push(s.labels[0].clone())),
        AnimateError::DuplicateName {
            kind: "label",
            name: "x".into()
        }
    );
    assert_eq!(
        refused(|s| s.traces.push(s.traces[0].clone())).to_string(),
        "two traces are named `contact`"
    );
    assert_eq!(
        refused(|s| s.items[1].shape = Shape::Box {
            size: [1.0, 0.0, 1.0]
        }),
        AnimateError::BadDimension {
            item: "board".into(),
            dimension: "size[1]",
            value: 0.0
        }
    );
    assert_eq!(
        refused(|s| s.items[0].shape = Shape::Disc {
            radius: 0.5,
            thickness: f64::INFINITY
        })
        .to_string(),
        "item `wheel`: its thickness is inf, not a positive finite number"
    );
    assert_eq!(
        refused(|s| s.items[0].shape = Shape::Sphere { radius: -1.0 }),
        AnimateError::BadDimension {
            item: "wheel".into(),
            dimension: "radius",
            value: -1.0
        }
    );
    assert_eq!(
        refused(|s| s.items[0].shape = Shape::Segment { length: f64::NAN }).to_string(),
        "item `wheel`: its length is NaN, not a positive finite number"
    );
    assert_eq!(
        refused(|s| {
            s.items[1].poses.pop();
        }),
        AnimateError::WrongLength {
            kind: "item",
            name: "board".into(),
            found: 2,
            frames: 3
        }
    );
    assert_eq!(
        refused(|s| s.labels[0].values.push(1.0)).to_string(),
        "label `x` has 4 values for 3 frames"
    );
    assert_eq!(
        refused(|s| s.traces[0].points.clear()),
        AnimateError::WrongLength {
            kind: "trace",
            name: "contact".into(),
            found: 0,
            frames: 3
        }
    );
    assert_eq!(
        refused(|s| s.items[1].poses[2].position[1] = f64::NEG_INFINITY).to_string(),
        "item `board`, frame 2: position[1] -inf is not a finite number"
    );
    // NaN is not equal to itself: the fields one by one
    match refused(|s| s.items[0].poses[1].quaternion[3] = f64::NAN) {
        AnimateError::NotFinite {
            kind: "item",
            name,
            frame: 1,
            what,
            value,
        } => {
            assert_eq!((name.as_str(), what.as_str()), ("wheel", "quaternion[3]"));
            assert!(value.is_nan());
        }
        other => panic!("not the expected error: {other:?}"),
    }
    assert_eq!(
        refused(|s| s.labels[0].values[0] = f64::NAN).to_string(),
        "label `x`, frame 0: value NaN is not a finite number"
    );
    assert_eq!(
        refused(|s| s.traces[0].points[2][2] = f64::INFINITY).to_string(),
        "trace `contact`, frame 2: point[2] inf is not a finite number"
    );
    assert_eq!(
        refused(|s| s.items[0].poses[1].quaternion = [0.0, 0.0, 0.0, 0.0]),
        AnimateError::NotUnitQuaternion {
            item: "wheel".into(),
            frame: 1,
            norm: 0.0
        }
    );
    assert_eq!(
        refused(|s| s.items[0].poses[2].quaternion = [1.0, 0.0, 0.0, 1.0]).to_string(),
        format!(
            "item `wheel`, frame 2: the quaternion's norm is {}, not 1",
            2f64.sqrt()
        )
    );
}

#[test]
fn a_quaternion_within_the_tolerance_of_unit_norm_is_taken() {
    let mut scene = scene();
    scene.items[0].poses[0].quaternion = [0.0, 0.0, 0.0, 1.0 + 0.5 * QUATERNION_NORM_TOLERANCE];
    page(&scene).unwrap();
}

#[test]
fn the_embedded_numbers_parse_back_to_the_same_doubles() {
    let awkward = [
        0.1,
        1.0 / 3.0,
        -2.0 / 3.0,
        std::f64::consts::PI,
        1e-300,
        5e-324,
        f64::MAX,
        f64::MIN_POSITIVE,
        -0.0,
        1e21,
        123_456_789.123_456_79,
        0.1 + 0.2,
        2f64.powi(53) + 2.0,
        1.0 - f64::EPSILON,
    ];
    let n = awkward.len();
    let at = |k: usize, shift: usize| awkward[(k + shift) % n];
    let times: Vec<f64> = (0..n).map(|k| k as f64 * 0.1 + 1.0 / 3.0).collect();
    let quaternion = |k: usize| {
        let angle = at(k, 0).abs().min(10.0) + 0.1 * k as f64;
        let (s, c) = (angle / 2.0).sin_cos();
        let axis = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
        [s * axis[0], s * axis[1], s * axis[2], c]
    };
    let scene = Scene {
        title: "numbers".into(),
        note: Some("1.5 and 2e3 in a note are not numbers of the data".into()),
        items: vec![
            Item {
                name: "ball 7".into(),
                shape: Shape::Sphere { radius: 1.0 / 7.0 },
                poses: (0..n)
                    .map(|k| Pose {
                        position: [at(k, 0), at(k, 1), at(k, 2)],
                        quaternion: quaternion(k),
                    })
                    .collect(),
            },
            Item {
                name: "rod".into(),
                shape: Shape::Segment { length: 0.3 },
                poses: (0..n)
                    .map(|k| Pose::at([at(k, 3), at(k, 4), at(k, 5)]))
                    .collect(),
            },
            Item {
                name: "board".into(),
                shape: Shape::Box {
                    size: [0.1, 1e-3, 2.0 / 3.0],
                },
                poses: (0..n)
                    .map(|k| Pose::at([at(k, 6), -at(k, 7), at(k, 8)]))
                    .collect(),
            },
            Item {
                name: "wheel".into(),
                shape: Shape::Disc {
                    radius: 0.7,
                    thickness: 1.0 / 30.0,
                },
                poses: (0..n)
                    .map(|k| Pose::at([at(k, 9), at(k, 10), at(k, 11)]))
                    .collect(),
            },
        ],
        labels: vec![
            Label {
                name: "x".into(),
                values: (0..n).map(|k| at(k, 12)).collect(),
            },
            Label {
                name: "theta".into(),
                values: (0..n).map(|k| -at(k, 13)).collect(),
            },
        ],
        traces: vec![Trace {
            name: "path".into(),
            points: (0..n).map(|k| [at(k, 1), at(k, 5), at(k, 9)]).collect(),
        }],
        times,
    };
    let html = page(&scene).unwrap();
    let json = embedded(&html);

    let mut expected = scene.times.clone();
    for item in &scene.items {
        expected.extend(item.shape.dimensions().into_iter().map(|(_, value)| value));
        expected.extend(item.poses.iter().flat_map(|pose| pose.position));
        expected.extend(item.poses.iter().flat_map(|pose| pose.quaternion));
    }
    for label in &scene.labels {
        expected.extend(&label.values);
    }
    for trace in &scene.traces {
        expected.extend(trace.points.iter().flatten());
    }
    let found = number_tokens(json);
    assert_eq!(found.len(), expected.len());
    for (i, (found, expected)) in found.iter().zip(&expected).enumerate() {
        assert_eq!(
            found.to_bits(),
            expected.to_bits(),
            "number {i}: {found} written for {expected}"
        );
    }

    // valid JSON, the strings intact
    let value: serde_json::Value = serde_json::from_str(json).unwrap();
    assert_eq!(value["title"], "numbers");
    assert_eq!(value["note"], scene.note.as_deref().unwrap());
    assert_eq!(value["items"][0]["name"], "ball 7");
    assert_eq!(value["items"][0]["shape"], "sphere");
    assert_eq!(value["items"][2]["shape"], "box");
    assert_eq!(value["items"][3]["shape"], "disc");
    assert_eq!(value["items"][1]["shape"], "segment");
    assert_eq!(value["labels"][1]["name"], "theta");
    assert_eq!(value["traces"][0]["name"], "path");
}

#[test]
fn text_cannot_end_the_data_or_break_the_markup() {
    let mut scene = scene();
    let hostile = "</script><script>alert(1)</script><!-- \"quoted\" & \\ \u{2028} \n\t\u{1}";
    scene.title = hostile.into();
    scene.note = Some(hostile.into());
    scene.items[0].name = hostile.into();
    scene.labels[0].name = "<b>x</b>".into();
    let html = page(&scene).unwrap();
    let json = embedded(&html);
    assert!(!json.contains('<'));
    let value: serde_json::Value = serde_json::from_str(json).unwrap();
    assert_eq!(value["title"], hostile);
    assert_eq!(value["note"], hostile);
    assert_eq!(value["items"][0]["name"], hostile);
    assert_eq!(value["labels"][0]["name"], "<b>x</b>");
    assert!(!html.contains("<script>alert"));
    assert!(html.contains("<title>&lt;/script&gt;&lt;script&gt;alert(1)&lt;/script&gt;&lt;!-- &quot;quoted&quot; &amp;"));
    assert!(html.contains("<p id=\"note\">&lt;/script&gt;"));
}

#[test]
fn the_inlined_scripts_cannot_end_their_element() {
    for (name, script) in [
        ("three.min.js", THREE),
        ("page.js", SCRIPT),
        ("page.css", STYLE),
    ] {
        let lower = script.to_ascii_lowercase();
        assert!(
            !lower.contains("</script") && !lower.contains("</style"),
            "{name} would end its element"
        );
        assert!(!lower.contains("<!--"), "{name} holds <!--");
    }
}

#[test]
fn the_page_names_no_external_address() {
    let html = page(&scene()).unwrap();
    // The XHTML namespace that three.js passes to createElementNS is a
    // name, never fetched; no other address appears.
    let rest = html.replace("http://www.w3.org/1999/xhtml", "");
    for pattern in [
        "http:", "https:", "//cdn", "src=", "href=", "@import", "url(",
    ] {
        assert!(!rest.contains(pattern), "the page holds {pattern}");
    }
}

#[test]
fn the_bundle_keeps_three_s_licence_header() {
    assert!(THREE.starts_with("/**\n * @license\n * Copyright 2010-2026 Three.js Authors\n * SPDX-License-Identifier: MIT\n */\n"));
    assert!(THREE.contains("three 0.187.0 with OrbitControls"));
}
