//! The template generator on the tiny preset's homes: determinism, grounding, turns, rooms,
//! unique coarse descriptions, styles, variety and chaining.

use crate::instructions_fixture;
use vlnverse_score::route::env_side;

use glam::Vec2;
use instructions_fixture::{paths, worlds, Ctx, Sample, World};
use std::collections::BTreeSet;
use vlnverse_env::scene_graph::{rooms_along_path, side_of, yaw_from_direction};
use vlnverse_env::{ObjectId, Scene};
use vlnverse_instructions::{
    check_grounding, coarse_expression, lexicon, InstructionGenerator, PathContext,
    TemplateGenerator,
};
use vlnverse_score::{Instruction, Role, Side, Style};

fn gen() -> TemplateGenerator {
    TemplateGenerator::default()
}

/// Non-structure objects with a unique description, and a path from a random navigable point
/// to the free point nearest to the object.
fn coarse_cases(w: &World, seed: u64) -> Vec<(ObjectId, Sample)> {
    let starts = paths(w, 40, seed);
    let mut out = Vec::new();
    for (k, o) in w
        .scene
        .objects
        .iter()
        .filter(|o| !o.is_structure())
        .enumerate()
    {
        if w.graph.referring_expression(&w.scene, o.id).is_none() {
            continue;
        }
        let c = o.bbox.center();
        let Some(goal) = w.maps.navigable.nearest_free(Vec2::new(c.x, c.z), 2.0) else {
            continue;
        };
        let start = &starts[k % starts.len()].path[0];
        let Some(p) = vlnverse_env::geodesic::shortest_path(
            &w.maps.navigable,
            Vec2::new(start[0], start[2]),
            goal,
        )
        .expect("finite") else {
            continue;
        };
        if p.points.len() < 2 {
            continue;
        }
        out.push((
            o.id,
            Sample {
                path: p.points.iter().map(|q| [q.x, 0.0, q.y]).collect(),
                start_yaw: 0.3 * k as f32,
            },
        ));
    }
    out
}

#[test]
fn fine_same_seed_same_text_and_seeds_vary() {
    let ws = worlds(2);
    let g = gen();
    let mut distinct = BTreeSet::new();
    let mut total = 0;
    for w in &ws {
        for s in paths(w, 10, 1) {
            let ctx = w.ctx(&s);
            let a = g.fine(&ctx, 42).unwrap();
            let b = g.fine(&ctx, 42).unwrap();
            assert_eq!(a, b);
            for seed in 0..4 {
                distinct.insert(g.fine(&ctx, seed).unwrap().instruction_text);
                total += 1;
            }
        }
    }
    // Different seeds give different wording for (nearly) every path.
    assert!(
        distinct.len() * 10 >= total * 9,
        "{} of {total}",
        distinct.len()
    );
}

/// Independent side check with `side_of`: some point of segment `i` closest to the object
/// (within 2 cm) sees the footprint centre on the stated side.
fn side_holds(scene: &Scene, path: &[[f32; 3]], g: &vlnverse_score::GroundedObject) -> bool {
    let o = scene.object(g.object_id).expect("object exists");
    let (lo, hi) = (
        Vec2::new(o.bbox.min[0], o.bbox.min[2]),
        Vec2::new(o.bbox.max[0], o.bbox.max[2]),
    );
    let center = (lo + hi) * 0.5;
    let pts: Vec<Vec2> = path.iter().map(|p| Vec2::new(p[0], p[2])).collect();
    let i = g.path_index.expect("index") as usize;
    let (a, b, dir) = if i + 1 < pts.len() {
        (pts[i], pts[i + 1], pts[i + 1] - pts[i])
    } else {
        let n = pts.len();
        (pts[i], pts[i], pts[n - 1] - pts[n - 2])
    };
    let yaw = yaw_from_direction(dir);
    let cand: Vec<(Vec2, f32)> = (0..=200)
        .map(|k| {
            let p = a.lerp(b, k as f32 / 200.0);
            (p, (p.clamp(lo, hi) - p).length())
        })
        .collect();
    let dmin = cand.iter().map(|c| c.1).fold(f32::INFINITY, f32::min);
    cand.iter()
        .filter(|c| c.1 <= dmin + 0.025)
        .any(|c| Some(env_side(side_of(c.0, yaw, center))) == g.side)
}

#[test]
fn fine_grounding_exists_near_path_and_on_stated_side() {
    let g = gen();
    let mut landmarks = 0;
    let mut lateral = 0;
    for (wi, w) in worlds(5).iter().enumerate() {
        for s in paths(w, 12, 10 + wi as u64) {
            let ctx = w.ctx(&s);
            let ins = g.fine(&ctx, 7).unwrap();
            let problems = check_grounding(&ctx, &ins, 3.0);
            assert!(
                problems.is_empty(),
                "{problems:?}\n{}",
                ins.instruction_text
            );
            for gr in &ins.grounding {
                assert!(w.scene.object(gr.object_id).is_some());
                assert!(side_holds(&w.scene, &s.path, gr), "{gr:?}");
                if gr.role == Role::Landmark {
                    landmarks += 1;
                    assert_ne!(gr.side, Some(Side::Behind));
                    lateral += usize::from(matches!(gr.side, Some(Side::Left | Side::Right)));
                    // The text names the landmark's class (by one of its names).
                    let class = vlnverse_env::SemanticClass::from_name(&gr.class).unwrap();
                    let names = vlnverse_instructions::lexicon::class_names(class);
                    // As whole words: "urn" is in "turn".
                    let words: Vec<&str> = ins
                        .instruction_text
                        .split(|c: char| !c.is_alphanumeric() && c != '\'')
                        .collect();
                    // A group is named in the plural ("the two doors").
                    let plurals: Vec<String> = names
                        .iter()
                        .map(|n| vlnverse_instructions::lexicon::plural(n))
                        .collect();
                    // Things of several classes are named by their kind ("the appliances").
                    let kinds = vlnverse_instructions::lexicon::kind_names(class);
                    let forms = names
                        .iter()
                        .copied()
                        .chain(plurals.iter().map(String::as_str))
                        .chain(kinds.iter().copied());
                    assert!(
                        forms.clone().any(|n| {
                            let k = n.split(' ').count();
                            words
                                .windows(k)
                                .any(|w| w.join(" ").eq_ignore_ascii_case(n))
                        }),
                        "{names:?}: {}",
                        ins.instruction_text
                    );
                }
            }
        }
    }
    assert!(landmarks >= 20, "only {landmarks} landmarks named");
    assert!(lateral >= 10, "only {lateral} landmarks on a side");
}

#[test]
fn fine_names_the_rooms_entered() {
    let g = gen();
    // With no object to stop at, the stop names the room (or, staying in one, a place in it).
    let roomy = TemplateGenerator::new(vlnverse_instructions::TemplateConfig {
        end_object_distance: 0.01,
        ..Default::default()
    })
    .unwrap();
    let (mut transitions, mut single) = (0, 0);
    for (wi, w) in worlds(5).iter().enumerate() {
        for s in paths(w, 10, 100 + wi as u64) {
            let path3: Vec<glam::Vec3> = s.path.iter().map(|p| glam::Vec3::from(*p)).collect();
            let rooms = rooms_along_path(&w.scene, &path3);
            let ins = g.fine(&w.ctx(&s), 3).unwrap();
            // A walk that never leaves its room is not told to enter one.
            if rooms.len() <= 1 {
                single += 1;
                let t = roomy.fine(&w.ctx(&s), 3).unwrap().instruction_text;
                let t = t.to_lowercase();
                let entering = ["enter ", "get into ", "once you are in ", "are inside "];
                assert!(!entering.iter().any(|e| t.contains(e)), "{t}");
            }
            for &(_, r) in rooms.iter().skip(1) {
                transitions += 1;
                let kind = w.scene.room(r).unwrap().kind.words();
                assert!(
                    ins.instruction_text.contains(&kind),
                    "{kind}: {}",
                    ins.instruction_text
                );
            }
        }
    }
    assert!(transitions >= 10, "only {transitions} room changes sampled");
    assert!(single >= 3, "only {single} walks within one room sampled");
}

/// A path far outside the home: no landmark, no room, only turns.
fn open_path(points: &[(f32, f32)], start_yaw: f32) -> Sample {
    Sample {
        path: points
            .iter()
            .map(|&(x, z)| [x + 500.0, 0.0, z + 500.0])
            .collect(),
        start_yaw,
    }
}

#[test]
fn fine_follows_the_turns_of_the_path() {
    let w = &worlds(1)[0];
    let g = gen();
    // Facing -Z (yaw 0), walk 5 m along -Z, then turn towards +X: a right turn.
    let right = open_path(&[(0.0, 0.0), (0.0, -5.0), (5.0, -5.0)], 0.0);
    let left = open_path(&[(0.0, 0.0), (0.0, -5.0), (-5.0, -5.0)], 0.0);
    let straight = open_path(&[(0.0, 0.0), (0.0, -5.0), (0.1, -10.0)], 0.0);
    let behind = open_path(&[(0.0, 0.0), (0.0, 5.0)], 0.0);
    for seed in 0..20 {
        let r = g.fine(&w.ctx(&right), seed).unwrap();
        assert!(
            r.instruction_text.contains("right") && !r.instruction_text.contains("left"),
            "{}",
            r.instruction_text
        );
        assert!(r.grounding.is_empty());
        let l = g.fine(&w.ctx(&left), seed).unwrap();
        assert!(
            l.instruction_text.contains("left") && !l.instruction_text.contains("right"),
            "{}",
            l.instruction_text
        );
        let s = g.fine(&w.ctx(&straight), seed).unwrap();
        assert!(
            !s.instruction_text.contains("left") && !s.instruction_text.contains("right"),
            "{}",
            s.instruction_text
        );
        let b = g
            .fine(&w.ctx(&behind), seed)
            .unwrap()
            .instruction_text
            .to_lowercase();
        assert!(
            [
                "around",
                "opposite",
                "u-turn",
                "turn back",
                "180 degrees",
                "eighty degrees"
            ]
            .iter()
            .any(|k| b.contains(k)),
            "{b}"
        );
    }
}

#[test]
fn coarse_descriptions_pick_out_exactly_the_target() {
    let g = gen();
    let mut checked = 0;
    for (wi, w) in worlds(5).iter().enumerate() {
        for (target, s) in coarse_cases(w, wi as u64) {
            let ctx = w.ctx(&s);
            let mut texts = BTreeSet::new();
            for style in Style::ALL {
                let expr = coarse_expression(&ctx, target, style).unwrap();
                assert_eq!(
                    expr.matches(&w.scene, &w.graph),
                    vec![target],
                    "{}",
                    expr.text()
                );
                let ins = g.coarse(&ctx, target, style, 5).unwrap();
                assert_eq!(ins.style, Some(style));
                // Every part of the description is in the text (spelled as the scene spells
                // it: some writers write "gray").
                let t = &ins.instruction_text.replace("gray", "grey");
                // The target goes by its class's name or another name of the object.
                let obj = w.scene.object(target).unwrap();
                let names = vlnverse_instructions::lexicon::object_names(obj);
                assert!(names.iter().any(|n| t.contains(n)), "{t}");
                if let Some(c) = &expr.color {
                    assert!(names.iter().any(|n| t.contains(&format!("{c} {n}"))), "{t}");
                }
                // Support and reference by their colour and any of their names.
                for m in expr.support.iter().chain(&expr.reference) {
                    let o = w.scene.object(m.object).unwrap();
                    let said = vlnverse_instructions::lexicon::object_names(o)
                        .iter()
                        .any(|n| match &m.color {
                            Some(c) => t.contains(&format!("{c} {n}")),
                            None => t.contains(n),
                        });
                    assert!(said, "{t}");
                }
                if let Some(r) = &expr.room {
                    assert!(t.contains(&r.kind.words()), "{t}");
                }
                // Grounding: the target (at the end of the path) and its reference objects.
                assert_eq!(ins.grounding[0].object_id, target);
                assert_eq!(ins.grounding[0].role, Role::Target);
                let only_target = Instruction {
                    grounding: ins.grounding[..1].to_vec(),
                    ..ins.clone()
                };
                let p = check_grounding(&ctx, &only_target, 3.0);
                assert!(p.is_empty(), "{p:?}");
                let p = check_grounding(&ctx, &ins, 6.0);
                assert!(p.is_empty(), "{p:?}");
                texts.insert(t.clone());
            }
            assert_eq!(texts.len(), 3, "styles read alike: {texts:?}");
            checked += 1;
        }
    }
    assert!(checked >= 30, "only {checked} targets checked");
}

#[test]
fn coarse_styles_have_their_own_register() {
    let g = gen();
    let w = &worlds(1)[0];
    let cases = coarse_cases(w, 9);
    assert!(!cases.is_empty());
    for (target, s) in cases.iter().take(10) {
        let ctx = w.ctx(s);
        for seed in 0..5 {
            let f = g
                .coarse(&ctx, *target, Style::Formal, seed)
                .unwrap()
                .instruction_text;
            let n = g
                .coarse(&ctx, *target, Style::Natural, seed)
                .unwrap()
                .instruction_text;
            let c = g
                .coarse(&ctx, *target, Style::Casual, seed)
                .unwrap()
                .instruction_text;
            assert!(f.starts_with(char::is_uppercase) && f.ends_with('.'), "{f}");
            assert!(n.starts_with(char::is_uppercase) && n.ends_with('.'), "{n}");
            assert!(
                c.starts_with(char::is_lowercase) && !c.ends_with('.'),
                "{c}"
            );
            assert_eq!(
                g.coarse(&ctx, *target, Style::Casual, seed)
                    .unwrap()
                    .instruction_text,
                c
            );
        }
    }
}

fn sentences(text: &str) -> Vec<String> {
    text.split(". ")
        .map(|s| s.trim().trim_end_matches('.').to_string())
        .filter(|s| !s.is_empty())
        .collect()
}

#[test]
fn instructions_do_not_read_alike() {
    let g = gen();
    let (mut fine_all, mut fine_distinct) = (0usize, BTreeSet::new());
    let (mut coarse_all, mut coarse_distinct) = (0usize, BTreeSet::new());
    for (wi, w) in worlds(5).iter().enumerate() {
        for (k, s) in paths(w, 60, 1000 + wi as u64).iter().enumerate() {
            let ins = g.fine(&w.ctx(s), k as u64).unwrap();
            for sen in sentences(&ins.instruction_text) {
                fine_all += 1;
                fine_distinct.insert(sen);
            }
        }
        for (k, (target, s)) in coarse_cases(w, 50 + wi as u64).iter().enumerate() {
            for style in Style::ALL {
                for seed in 0..3 {
                    let ins = g
                        .coarse(&w.ctx(s), *target, style, k as u64 * 7 + seed)
                        .unwrap();
                    coarse_all += 1;
                    coarse_distinct.insert(ins.instruction_text);
                }
            }
        }
    }
    let fr = fine_distinct.len() as f64 / fine_all as f64;
    let cr = coarse_distinct.len() as f64 / coarse_all as f64;
    eprintln!(
        "fine: {} distinct of {fine_all} sentences ({fr:.2}); coarse: {} of {coarse_all} ({cr:.2})",
        fine_distinct.len(),
        coarse_distinct.len()
    );
    assert!(fine_all >= 300);
    assert!(fr >= 0.8, "fine distinct-sentence ratio {fr:.2}");
    assert!(cr >= 0.85, "coarse distinct ratio {cr:.2}");
}

#[test]
fn chain_joins_parts_in_order() {
    let g = gen();
    let w = &worlds(1)[0];
    let cases = coarse_cases(w, 3);
    assert!(cases.len() >= 3);
    let parts: Vec<Instruction> = cases[..3]
        .iter()
        .zip(Style::ALL)
        .map(|((t, s), style)| g.coarse(&w.ctx(s), *t, style, 1).unwrap())
        .collect();
    let c = g.chain(&parts, 11).unwrap();
    assert_eq!(c, g.chain(&parts, 11).unwrap());
    // Each sub-instruction is its part's text, less an opener ("Okay, ") the chain replaces.
    assert_eq!(c.sub_instructions.len(), parts.len());
    for (sub, p) in c.sub_instructions.iter().zip(&parts) {
        let (sub, full) = (sub.to_lowercase(), p.instruction_text.to_lowercase());
        assert!(
            full.ends_with(&sub) && sub.split(' ').count() >= 3,
            "{sub} / {full}"
        );
    }
    let texts = &c.sub_instructions;
    assert_eq!(c.style, None, "mixed styles have no common style");
    assert_eq!(
        c.grounding.len(),
        parts.iter().map(|p| p.grounding.len()).sum::<usize>()
    );
    // Each part appears, in order, lower-cased at its start and without its full stop.
    let lower = c.instruction_text.to_lowercase();
    let mut at = 0;
    for t in texts {
        let body = t.trim_end_matches('.').to_lowercase();
        let pos = lower[at..]
            .find(&body)
            .unwrap_or_else(|| panic!("{body} not in {lower}"));
        at += pos + body.len();
    }
    assert!(
        c.instruction_text.starts_with(char::is_uppercase) && c.instruction_text.ends_with('.')
    );
    let same: Vec<Instruction> = parts
        .iter()
        .take(2)
        .map(|p| Instruction {
            style: Some(Style::Formal),
            ..p.clone()
        })
        .collect();
    assert_eq!(g.chain(&same, 0).unwrap().style, Some(Style::Formal));
    assert!(g.chain(&[], 0).is_err());
    // Casual parts make one lower-case line without a full stop, the parts in order.
    let casual: Vec<Instruction> = cases[..3]
        .iter()
        .map(|(t, s)| g.coarse(&w.ctx(s), *t, Style::Casual, 4).unwrap())
        .collect();
    let c = g.chain(&casual, 5).unwrap();
    assert_eq!(c.style, Some(Style::Casual));
    let t = &c.instruction_text;
    assert!(
        t.starts_with(char::is_lowercase) && !t.ends_with('.'),
        "{t}"
    );
    let mut at = 0;
    for s in &c.sub_instructions {
        let pos = t[at..]
            .find(s.as_str())
            .unwrap_or_else(|| panic!("{s} not in {t}"));
        at += pos + s.len();
    }
}

#[test]
fn bad_inputs_give_clear_errors() {
    let g = gen();
    let w = &worlds(1)[0];
    let one = Sample {
        path: vec![[0.0, 0.0, 0.0]],
        start_yaw: 0.0,
    };
    let e = g.fine(&w.ctx(&one), 0).unwrap_err().to_string();
    assert!(e.contains("path") && e.contains("1 points"), "{e}");
    let nan = Sample {
        path: vec![[0.0, 0.0, 0.0], [f32::NAN, 0.0, 1.0]],
        start_yaw: 0.0,
    };
    let e = g.fine(&w.ctx(&nan), 0).unwrap_err().to_string();
    assert!(e.contains("path[1]"), "{e}");
    let wall = w
        .scene
        .objects
        .iter()
        .find(|o| o.is_structure())
        .unwrap()
        .id;
    let s = &paths(w, 1, 0)[0];
    let e = g
        .coarse(&w.ctx(s), wall, Style::Formal, 0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("target") && e.contains(&wall.to_string()), "{e}");
    let e = g
        .coarse(&w.ctx(s), 999_999, Style::Formal, 0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("999999"), "{e}");
    let bad = vlnverse_instructions::TemplateConfig {
        landmark_distance: -1.0,
        ..Default::default()
    };
    let e = TemplateGenerator::new(bad).unwrap_err().to_string();
    assert!(e.contains("landmark_distance"), "{e}");
}

#[test]
fn path_context_is_copy_for_callers() {
    // The pipeline builds one context per trajectory; it is a cheap copy.
    let w = &worlds(1)[0];
    let s = &paths(w, 1, 4)[0];
    let ctx: PathContext<'_> = w.ctx(s);
    let copy = ctx;
    assert_eq!(gen().fine(&ctx, 1).unwrap(), gen().fine(&copy, 1).unwrap());
}

/// A second turn the same way as the first is now and then said so ("turn right again",
/// "take another right", "bear left again"); a turn the other way never is.
#[test]
fn a_turn_the_same_way_again_is_said_so() {
    let w = &worlds(1)[0];
    let g = gen();
    let said = |text: &str| {
        let t = text.to_lowercase();
        t.contains("again") || t.contains("another") || t.contains("keep bearing")
    };
    // Right, then right again; right, then left.
    let twice = open_path(&[(0.0, 0.0), (0.0, -5.0), (5.0, -5.0), (5.0, 0.0)], 0.0);
    let back = open_path(&[(0.0, 0.0), (0.0, -5.0), (5.0, -5.0), (5.0, -10.0)], 0.0);
    // Two slight bends to the left (about 29 and 35 degrees).
    let bends = open_path(&[(0.0, 0.0), (0.0, -5.0), (-2.5, -9.5), (-7.0, -11.7)], 0.0);
    let (mut again, mut slight) = (0, 0);
    for seed in 0..40 {
        again += usize::from(said(
            &g.fine(&w.ctx(&twice), seed).unwrap().instruction_text,
        ));
        let b = g.fine(&w.ctx(&back), seed).unwrap().instruction_text;
        assert!(!said(&b), "{b}");
        let s = g.fine(&w.ctx(&bends), seed).unwrap().instruction_text;
        assert!(!s.contains("right"), "{s}");
        slight += usize::from(said(&s));
    }
    assert!(again >= 5, "only {again} of 40");
    assert!(slight >= 3, "only {slight} of 40");
}

/// A coarse remark on how many of the target's class its room holds ("There are two chairs in
/// the room") gives the true count.
#[test]
fn a_count_remark_gives_the_true_number_in_the_room() {
    let g = gen();
    let mut said = 0;
    for (wi, w) in worlds(5).iter().enumerate() {
        for (target, s) in coarse_cases(w, wi as u64) {
            let ctx = w.ctx(&s);
            let o = w.scene.object(target).unwrap();
            // The plurals of the object's names, longest first ("kitchen counters" before
            // "counters").
            let mut plurals: Vec<String> = lexicon::object_names(o)
                .into_iter()
                .map(lexicon::plural)
                .collect();
            plurals.sort_by_key(|p| std::cmp::Reverse(p.len()));
            let n = w
                .scene
                .objects
                .iter()
                .filter(|x| x.class == o.class && x.room == o.room)
                .count();
            for style in Style::ALL {
                for seed in 0..40 {
                    let t = g
                        .coarse(&ctx, target, style, seed)
                        .unwrap()
                        .instruction_text;
                    // An opener ending in a comma runs on in lower case.
                    let mut after_comma = t.split(", ").skip(1).filter_map(|x| x.chars().next());
                    assert!(after_comma.all(|c| !c.is_uppercase()), "{t}");
                    let t = t.replace("gray", "grey");
                    let remark = plurals.iter().find(|names| {
                        [" in the room", " in there"]
                            .iter()
                            .any(|end| t.contains(&format!(" {names}{end}")))
                            || (t.contains("room has ") && t.contains(names.as_str()))
                    });
                    if let Some(names) = remark {
                        said += 1;
                        let want = format!("{} {names}", lexicon::number_word(n as u32));
                        assert!(t.contains(&want), "{t} (the room holds {n})");
                    }
                }
            }
        }
    }
    assert!(said > 0, "no count remark in any coarse instruction");
}

/// "The cup closest to the lamp" is said only of the one of its class nearest the lamp.
#[test]
fn closest_is_said_only_of_the_closest() {
    let g = gen();
    let mut said = 0;
    let centre = |o: &vlnverse_env::SceneObject| {
        Vec2::new(
            (o.bbox.min[0] + o.bbox.max[0]) * 0.5,
            (o.bbox.min[2] + o.bbox.max[2]) * 0.5,
        )
    };
    for (wi, w) in worlds(5).iter().enumerate() {
        for (target, s) in coarse_cases(w, wi as u64) {
            let ctx = w.ctx(&s);
            for style in Style::ALL {
                let expr = coarse_expression(&ctx, target, style).unwrap();
                let Some(r) = expr.reference.as_ref() else {
                    continue;
                };
                for seed in 0..30 {
                    let t = g
                        .coarse(&ctx, target, style, seed)
                        .unwrap()
                        .instruction_text;
                    if !(t.contains(" closest to ") || t.contains(" nearest ")) {
                        continue;
                    }
                    said += 1;
                    // Closest as people judge it next to a large reference: the distance
                    // from each object's centre to the reference's footprint.
                    let o = w.scene.object(target).unwrap();
                    let rb = &w.scene.object(r.object).unwrap().bbox;
                    let to_ref = |p: Vec2| {
                        let dx = (rb.min[0] - p.x).max(p.x - rb.max[0]).max(0.0);
                        let dz = (rb.min[2] - p.y).max(p.y - rb.max[2]).max(0.0);
                        Vec2::new(dx, dz).length()
                    };
                    let mine = to_ref(centre(o));
                    for x in w.scene.objects.iter() {
                        if x.class == o.class && x.id != o.id {
                            assert!(to_ref(centre(x)) > mine, "{t}");
                        }
                    }
                }
            }
        }
    }
    assert!(said > 0, "no coarse instruction said closest");
}

/// A room keeps the name it was first given through an instruction: the living room is not
/// "the lounge" or "the den" a sentence later (a home has one living room).
#[test]
fn the_living_room_keeps_one_name_through_an_instruction() {
    let g = gen();
    let names = [
        "living room",
        "lounge",
        "family room",
        "sitting room",
        "den",
    ];
    let mut seen = 0;
    for w in worlds(6).iter() {
        for s in paths(w, 12, 3) {
            for seed in 0..25 {
                let t = g
                    .fine(&w.ctx(&s), seed)
                    .unwrap()
                    .instruction_text
                    .to_lowercase();
                let used: Vec<&str> = names
                    .iter()
                    .copied()
                    .filter(|n| {
                        t.match_indices(n).any(|(i, _)| {
                            let before = t[..i].chars().next_back();
                            let after = t[i + n.len()..].chars().next();
                            // "lounge" in "chaise lounge" names a seat, not the room.
                            let seat = *n == "lounge" && t[..i].ends_with("chaise ");
                            before.is_none_or(|c| !c.is_alphanumeric())
                                && after.is_none_or(|c| !c.is_alphanumeric())
                                && !seat
                        })
                    })
                    .collect();
                seen += usize::from(!used.is_empty());
                assert!(used.len() <= 1, "{used:?}: {t}");
            }
        }
    }
    assert!(seen > 0, "no instruction named the living room");
}

/// Glass panes of class window in `room` (a window is a pane and its frame).
fn windows_in(scene: &Scene, room: u32) -> usize {
    scene
        .objects
        .iter()
        .filter(|o| {
            o.class == vlnverse_env::SemanticClass::Window
                && o.room == Some(room)
                && o.material == "glass"
        })
        .count()
}

/// The material of `room`'s largest floor slab ("wood", "tile").
fn floor_material(scene: &Scene, room: u32) -> Option<String> {
    scene
        .objects
        .iter()
        .filter(|o| o.class == vlnverse_env::SemanticClass::Floor && o.room == Some(room))
        .max_by(|a, b| {
            let area = |o: &vlnverse_env::SceneObject| o.bbox.size().x * o.bbox.size().z;
            area(a).total_cmp(&area(b))
        })
        .map(|o| o.material.clone())
}

/// Whether `room` is a hallway with no furniture in it.
fn empty_hallway(scene: &Scene, room: u32) -> bool {
    scene
        .room(room)
        .is_some_and(|r| r.kind == vlnverse_env::RoomType::Hallway)
        && !scene
            .items()
            .any(|o| o.room == Some(room) && o.class.kind() == vlnverse_env::ClassKind::Furniture)
}

#[test]
fn a_room_remark_gives_its_true_windows_and_floor() {
    let g = gen();
    let (mut windows, mut floors, mut none, mut empty, mut changes) = (0, 0, 0, 0, 0);
    for (wi, w) in worlds(5).iter().enumerate() {
        for s in paths(w, 10, 300 + wi as u64) {
            let path3: Vec<glam::Vec3> = s.path.iter().map(|p| glam::Vec3::from(*p)).collect();
            let entered: Vec<u32> = rooms_along_path(&w.scene, &path3)
                .iter()
                .skip(1)
                .map(|&(_, r)| r)
                .collect();
            let floor_of = |r: u32| floor_material(&w.scene, r);
            for seed in 0..90 {
                let t = g.fine(&w.ctx(&s), seed).unwrap().instruction_text;
                for sentence in sentences(&t) {
                    let sentence = sentence.to_lowercase();
                    let n = if sentence == "there is a window in this room"
                        || sentence == "the room has a window"
                    {
                        Some(1)
                    } else {
                        (2..=4).find(|&n| {
                            let word = lexicon::number_word(n as u32);
                            sentence == format!("the room has {word} windows")
                                || sentence == format!("there are {word} windows in this room")
                        })
                    };
                    // No window: only said of a room that is not a hallway.
                    if [
                        "there are no windows in this room",
                        "the room has no windows",
                        "it is an interior room with no windows",
                    ]
                    .contains(&sentence.as_str())
                    {
                        none += 1;
                        assert!(
                            entered.iter().any(|&r| windows_in(&w.scene, r) == 0
                                && w.scene.room(r).map(|x| x.kind)
                                    != Some(vlnverse_env::RoomType::Hallway)),
                            "no windowless room entered: {t}"
                        );
                    }
                    if [
                        "the hallway is empty",
                        "it is an empty hallway",
                        "there is no furniture in this hallway",
                    ]
                    .contains(&sentence.as_str())
                    {
                        empty += 1;
                        assert!(
                            entered.iter().any(|&r| empty_hallway(&w.scene, r)),
                            "no empty hallway entered: {t}"
                        );
                    }
                    // "The floor changes from wood to tile here": two rooms one after the
                    // other on the path with those floors.
                    let change = sentence
                        .strip_prefix("the floor changes from ")
                        .and_then(|x| x.strip_suffix(" here"))
                        .or_else(|| sentence.strip_prefix("here the floor changes from "))
                        .or_else(|| sentence.strip_prefix("you will notice the floor change from "))
                        .and_then(|x| x.split_once(" to "));
                    if let Some((a, b)) = change {
                        changes += 1;
                        let order: Vec<u32> = rooms_along_path(&w.scene, &path3)
                            .iter()
                            .map(|&(_, r)| r)
                            .collect();
                        assert!(
                            order
                                .windows(2)
                                .any(|p| floor_of(p[0]).as_deref() == Some(a)
                                    && floor_of(p[1]).as_deref() == Some(b)),
                            "no room with a {a} floor followed by one with {b}: {t}"
                        );
                    }
                    if let Some(n) = n {
                        windows += 1;
                        assert!(
                            entered.iter().any(|&r| windows_in(&w.scene, r) == n),
                            "{n} windows in none of the rooms entered: {t}"
                        );
                    }
                    let kind = match sentence.as_str() {
                        "the room has a tiled floor"
                        | "the floor is tiled"
                        | "this room has a tile floor" => Some("tile"),
                        "the room has a wooden floor"
                        | "the floor is wooden"
                        | "this room has a hardwood floor" => Some("wood"),
                        "the room has a carpeted floor" | "the floor is carpeted" => Some("carpet"),
                        "the room has a stone floor" | "this room has a stone tile floor" => {
                            Some("stone")
                        }
                        "the room has a concrete floor" | "the floor is bare concrete" => {
                            Some("concrete")
                        }
                        _ => None,
                    };
                    if let Some(kind) = kind {
                        floors += 1;
                        assert!(
                            entered
                                .iter()
                                .any(|&r| floor_of(r).as_deref() == Some(kind)),
                            "no {kind} floor in the rooms entered: {t}"
                        );
                    }
                }
            }
        }
    }
    // An empty hallway is rare in these homes: what is said of one is checked above.
    assert!(
        windows >= 3 && floors >= 3 && none >= 1 && changes >= 1,
        "only {windows} window, {none} no-window, {changes} floor-change and {floors} floor \
         remarks ({empty} empty-hallway)"
    );
}

/// "stop where the floor changes from tile to carpet": the goal is in a doorway between a room
/// with the first floor and one with the second.
#[test]
fn a_stop_where_the_floor_changes_is_in_a_doorway_between_those_floors() {
    let g = gen();
    let mut said = 0;
    for (wi, w) in worlds(6).iter().enumerate() {
        for s in paths(w, 12, 700 + wi as u64) {
            let end = s.path.last().unwrap();
            let end = Vec2::new(end[0], end[2]);
            for seed in 0..40 {
                let t = g.fine(&w.ctx(&s), seed).unwrap().instruction_text;
                // The stop, not a remark on a room entered ("Here the floor changes ..."):
                // "stop where the floor changes from X to Y", "wait where the X floor changes
                // to Y", "stop where the X meets the Y", "stop on the line between the X and
                // the Y".
                const MATERIALS: [&str; 5] = ["wood", "tile", "carpet", "stone", "concrete"];
                let Some(told) = sentences(&t).into_iter().find_map(|x| {
                    let x = x.to_lowercase();
                    let stop = x.contains("stop") || x.contains("wait");
                    let at = ["floor changes", " meets the ", "line between the "]
                        .iter()
                        .filter_map(|k| x.find(k))
                        .min()?;
                    let head = x[..at].rfind("where").or_else(|| x[..at].rfind("line"))?;
                    let named: Vec<&str> = x[head..]
                        .split(|c: char| !c.is_alphanumeric())
                        .filter(|w| MATERIALS.contains(w))
                        .collect();
                    (stop && named.len() == 2).then(|| (named[0].to_string(), named[1].to_string()))
                }) else {
                    continue;
                };
                let (from, to) = told;
                said += 1;
                let door = w.scene.doors.iter().find(|d| {
                    let c = Vec2::new(d.position[0], d.position[2]);
                    let floors: Vec<Option<String>> = d
                        .rooms
                        .iter()
                        .map(|&r| floor_material(&w.scene, r))
                        .collect();
                    c.distance(end) < 1.0
                        && floors.contains(&Some(from.clone()))
                        && floors.contains(&Some(to.clone()))
                });
                assert!(
                    door.is_some(),
                    "no doorway from {from} to {to} at the goal: {t}"
                );
            }
        }
    }
    assert!(said > 0, "no stop where the floor changes");
}

/// A count after the stop ("There are three chairs in the room.") gives the true number of the
/// end object's class in its room.
#[test]
fn a_fine_count_remark_gives_the_true_number_in_the_room() {
    let g = gen();
    let mut said = 0;
    for (wi, w) in worlds(5).iter().enumerate() {
        for s in paths(w, 12, 500 + wi as u64) {
            for seed in 0..60 {
                let ins = g.fine(&w.ctx(&s), seed).unwrap();
                let Some(end) = ins.grounding.iter().find(|x| x.role == Role::Target) else {
                    continue;
                };
                let o = w.scene.object(end.object_id).unwrap();
                let name = lexicon::class_names(o.class)[0];
                let names = lexicon::plural(name);
                // The remark follows the goal's description; a room entered on the way may be
                // counted too ("The room has two doors."), of its own doors.
                let all = sentences(&ins.instruction_text);
                let mentions = |t: &str| {
                    t.to_lowercase()
                        .split(|c: char| !c.is_alphanumeric())
                        .collect::<Vec<_>>()
                        .windows(name.split(' ').count())
                        .any(|w| w.join(" ") == name)
                };
                let Some(goal) = all.iter().rposition(|t| mentions(t)) else {
                    continue;
                };
                for sentence in &all[goal..] {
                    let told = (2..=6u32).find(|&k| {
                        let k = lexicon::number_word(k);
                        [
                            format!("There are {k} {names} in the room"),
                            format!("It is one of {k} {names} in the room"),
                            format!("The room has {k} {names}"),
                        ]
                        .contains(sentence)
                    });
                    if let Some(k) = told {
                        said += 1;
                        let n = w
                            .scene
                            .objects
                            .iter()
                            .filter(|x| x.class == o.class && x.room == o.room)
                            .count();
                        assert_eq!(k as usize, n, "{}", ins.instruction_text);
                    }
                }
            }
        }
    }
    assert!(said > 0, "no count remark in any fine instruction");
}
