//! Behaviour of the rapier simulator on hand-made scenes.

use crate::common::*;
use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f32::consts::{FRAC_PI_2, PI};
use vlnverse_env::{Motion, SemanticClass};
use vlnverse_sim::*;

fn sim(setting: CollisionSetting) -> RapierSimulator {
    RapierSimulator::new(SimConfig {
        setting,
        ..Default::default()
    })
    .unwrap()
}

fn xz(p: &vlnverse_env::Pose) -> Vec2 {
    Vec2::new(p.position[0], p.position[2])
}

#[test]
fn discrete_moves_never_pass_through_a_wall() {
    // A thin (2 cm) wall across the room at z = -2, and the room wall at z = -5.
    let scene = room_with(vec![wall(
        6,
        Vec3::new(0.0, 1.25, -2.0),
        Vec3::new(4.0, 1.25, 0.01),
    )]);
    let mut s = sim(CollisionSetting::Lenient);
    s.reset(&scene, at(0.0, 0.0, 0.0)).unwrap();
    for _ in 0..20 {
        let out = s.step(Action::MoveForward(action::MAX_FORWARD)).unwrap();
        assert!(
            out.pose.position[2] > -2.0 + 0.01 + 0.3 - 1e-3,
            "{:?}",
            out.pose
        );
    }
    let out = s.step(Action::MoveForward(1.0)).unwrap();
    assert!(out.collided && out.hit.contains(&6), "{out:?}");
    // Facing the outer wall diagonally: never leaves the room.
    s.reset(&scene, at(3.0, 3.0, -PI * 0.75)).unwrap();
    for _ in 0..20 {
        let p = s
            .step(Action::MoveForward(action::MAX_FORWARD))
            .unwrap()
            .pose;
        assert!(
            p.position[0] <= 5.0 - 0.3 + 1e-3 && p.position[2] <= 5.0 - 0.3 + 1e-3,
            "{p:?}"
        );
    }
}

#[test]
fn continuous_control_never_passes_through_a_wall_at_max_speed() {
    let scene = room_with(vec![wall(
        6,
        Vec3::new(0.0, 1.25, -2.0),
        Vec3::new(4.0, 1.25, 0.02),
    )]);
    let mut s = sim(CollisionSetting::Lenient);
    s.reset(&scene, at(0.0, 0.0, 0.0)).unwrap();
    let vmax = s.config().agent.max_linear_speed;
    for _ in 0..6 {
        let out = s
            .step(Action::Velocity {
                v: vmax * 10.0, // clamped to the agent's limit
                omega: 0.0,
                duration: 1.0,
            })
            .unwrap();
        assert!(out.pose.position[2] > -2.0 + 0.02, "{:?}", out.pose);
    }
    let p = s.pose().position;
    assert!(
        p[2] < -1.5,
        "agent should be pressed against the wall, is at {p:?}"
    );
}

/// Agent heading 30 degrees into the wall at z = -5 (inner face), 5 cm from touching it.
fn thirty_degrees_into_wall(sliding: bool) -> (Vec2, Vec2, Vec<StepOutcome>) {
    let mut cfg = SimConfig {
        setting: CollisionSetting::Lenient,
        ..Default::default()
    };
    cfg.agent.allow_sliding = sliding;
    let mut s = RapierSimulator::new(cfg).unwrap();
    // forward = (-sin yaw, -cos yaw); yaw = -60 deg gives (0.866, -0.5): 30 deg to the wall.
    let start = at(-2.0, -5.0 + 0.3 + 0.05, -PI / 3.0);
    s.reset(&room(), start).unwrap();
    let outs: Vec<_> = (0..8)
        .map(|_| s.step(Action::MoveForward(0.25)).unwrap())
        .collect();
    (xz(&start), xz(&s.pose()), outs)
}

#[test]
fn thirty_degrees_into_a_wall_slides_with_sliding_on() {
    let (a, b, outs) = thirty_degrees_into_wall(true);
    let d = b - a;
    // Without the wall the agent would go 2 m * cos 30 = 1.73 m along x; sliding keeps most.
    assert!(d.x > 1.5, "slid only {d:?}");
    assert!(b.y >= -5.0 + 0.3 - 1e-3, "went into the wall: {b:?}");
    assert!(outs.iter().any(|o| o.collided && o.hit == vec![2]));
    // Each blocked step loses the normal part 0.25 * sin 30 = 0.125 > 0.10: noticeable.
    assert!(outs.last().unwrap().noticeable);
}

#[test]
fn a_blocked_step_keeps_exactly_its_tangential_part() {
    let (_, _, outs) = thirty_degrees_into_wall(true);
    // Once against the wall, a 0.25 m step at 30 deg keeps 0.25 * cos 30 along the wall and
    // loses the normal part; the agent stays at the wall (skin 5 mm).
    for o in &outs[2..] {
        let [ax, az] = o.achieved;
        assert!((ax - 0.25 * 30f32.to_radians().cos()).abs() < 1e-3, "{o:?}");
        // The cast's contact normal on a cylinder is good to a fraction of a degree: mm jitter.
        assert!(az.abs() < 5e-3, "{o:?}");
        assert!((o.pose.position[2] - (-5.0 + 0.3)).abs() < 0.01, "{o:?}");
        assert!(o.collided && o.hit == vec![2]);
    }
}

#[test]
fn head_on_into_a_wall_stops_and_stays_put() {
    let mut s = sim(CollisionSetting::Lenient);
    s.reset(&room(), at(0.0, -4.0, 0.0)).unwrap();
    let outs: Vec<_> = (0..10)
        .map(|_| s.step(Action::MoveForward(0.25)).unwrap())
        .collect();
    // 0.7 m of free travel, then every step is blocked and achieves nothing.
    let first = outs[2].pose.position;
    assert!((first[2] - (-5.0 + 0.3)).abs() < 0.01, "{first:?}");
    for o in &outs[3..] {
        assert!(o.collided && o.noticeable && o.hit == vec![2], "{o:?}");
        assert!(Vec2::from(o.achieved).length() < 1e-3, "{o:?}");
        assert!((xz(&o.pose) - Vec2::new(first[0], first[2])).length() < 1e-3);
    }
}

#[test]
fn pushed_into_a_corner_stays_in_the_corner() {
    // Heading diagonally into the corner of walls 2 (z = -5) and 5 (x = +5).
    let mut s = sim(CollisionSetting::Lenient);
    s.reset(&room(), at(3.0, -3.0, -PI / 4.0)).unwrap();
    let mut last = None;
    for _ in 0..20 {
        let o = s.step(Action::MoveForward(0.25)).unwrap();
        let p = xz(&o.pose);
        assert!(p.x <= 5.0 - 0.3 + 1e-3 && p.y >= -5.0 + 0.3 - 1e-3, "{o:?}");
        last = Some(o);
    }
    let o = last.unwrap();
    let p = xz(&o.pose);
    assert!((p - Vec2::new(4.7, -4.7)).length() < 0.02, "{o:?}");
    assert!(Vec2::from(o.achieved).length() < 1e-3, "{o:?}");
    assert!(o.hit.contains(&2) || o.hit.contains(&5), "{o:?}");
}

#[test]
fn thirty_degrees_into_a_wall_stops_with_sliding_off() {
    let (a, b, outs) = thirty_degrees_into_wall(false);
    let d = b - a;
    // Free travel until contact is 0.05 / sin 30 = 0.1 m, then nothing.
    assert!(d.length() < 0.15, "moved {d:?}");
    assert!(b.y >= -5.0 + 0.3 - 1e-3);
    let last = outs.last().unwrap();
    assert!(last.collided && last.noticeable && Vec2::from(last.achieved).length() < 1e-3);
}

fn push_test(mass: f32, friction: f32) -> (Vec2, Vec2, Vec2, StepOutcome) {
    let furniture = boxed(
        6,
        SemanticClass::Chair,
        Vec3::new(0.0, 0.4, -1.0),
        Vec3::new(0.3, 0.4, 0.3),
        Motion::Dynamic,
        mass,
        friction,
    );
    let scene = room_with(vec![furniture]);
    let mut s = sim(CollisionSetting::Lenient);
    s.reset(&scene, at(0.0, 0.0, 0.0)).unwrap();
    let before = s.object_pose(6).unwrap();
    let out = s
        .step(Action::Velocity {
            v: 0.6,
            omega: 0.0,
            duration: 4.0,
        })
        .unwrap();
    let after = s.object_pose(6).unwrap();
    (xz(&before), xz(&after), xz(&out.pose), out)
}

#[test]
fn pushing_a_light_chair_moves_it() {
    let (before, after, agent, out) = push_test(10.0, 0.5);
    let moved = after - before;
    assert!(moved.y < -0.5, "chair moved only {moved:?}");
    assert!(agent.y < -0.8, "agent did not follow: {agent:?}");
    assert!(out.hit.contains(&6), "{out:?}");
}

#[test]
fn a_heavy_sofa_stops_the_agent() {
    let (before, after, agent, out) = push_test(200.0, 0.6);
    let moved = (after - before).length();
    assert!(moved < 0.05, "sofa moved {moved}");
    // Agent stops at the sofa face (z = -0.7) with its radius 0.3.
    assert!(agent.y > -0.45, "agent went through: {agent:?}");
    assert!(
        out.collided && out.noticeable && out.hit.contains(&6),
        "{out:?}"
    );
}

fn table_scene() -> vlnverse_env::Scene {
    room_with(vec![boxed(
        6,
        SemanticClass::DiningTable,
        Vec3::new(2.0, 0.4, 0.0),
        Vec3::new(0.5, 0.4, 0.5),
        Motion::Static,
        40.0,
        0.5,
    )])
}

#[test]
fn telhop_into_furniture_lands_on_the_nearest_free_spot() {
    let mut s = sim(CollisionSetting::Lenient);
    s.reset(&table_scene(), at(0.0, 0.0, 0.0)).unwrap();
    let out = s
        .step(Action::Waypoint {
            x: 2.1,
            z: 0.1,
            mode: WaypointMode::TelHop,
        })
        .unwrap();
    let p = xz(&out.pose);
    // Nearest free spot: the +x face at 2.5 plus the radius 0.3 -> x = 2.8, shift 0.7.
    let Some(Hop::Landed { shift }) = out.hop else {
        panic!("{out:?}")
    };
    assert!(
        (0.7 - 1e-3..=0.7 + 0.06).contains(&shift),
        "shift {shift}, at {p}"
    );
    assert!(s.is_free(p.x, p.y), "landed inside something at {p}");
    assert!((p - Vec2::new(2.1, 0.1)).length() <= 0.76);
    assert!(out.collided && out.noticeable && out.hit == vec![6]);
    assert!(!out.done && out.failure.is_none());
}

#[test]
fn telhop_to_a_free_spot_is_exact() {
    let mut s = sim(CollisionSetting::Strict);
    s.reset(&table_scene(), at(0.0, 0.0, 0.0)).unwrap();
    let out = s
        .step(Action::Waypoint {
            x: -1.0,
            z: 2.0,
            mode: WaypointMode::TelHop,
        })
        .unwrap();
    assert_eq!(xz(&out.pose), Vec2::new(-1.0, 2.0));
    assert_eq!(out.hop, Some(Hop::Landed { shift: 0.0 }));
    assert!(!out.collided && !out.noticeable && !out.done);
    // Heading faces the travel direction (-1, 2): yaw = atan2(1, -2).
    assert!((out.pose.yaw() - 1.0f32.atan2(-2.0)).abs() < 1e-5);
}

#[test]
fn telhop_without_a_free_spot_fails_and_says_so() {
    let big = boxed(
        6,
        SemanticClass::Bed,
        Vec3::new(2.0, 0.5, 0.0),
        Vec3::new(1.5, 0.5, 1.5),
        Motion::Static,
        80.0,
        0.5,
    );
    let mut cfg = SimConfig {
        setting: CollisionSetting::TelHop,
        hop_radius: 0.4,
        ..Default::default()
    };
    cfg.agent.allow_sliding = true;
    let mut s = RapierSimulator::new(cfg).unwrap();
    s.reset(&room_with(vec![big]), at(0.0, 0.0, 0.0)).unwrap();
    let out = s
        .step(Action::Waypoint {
            x: 2.0,
            z: 0.0,
            mode: WaypointMode::Drive,
        })
        .unwrap();
    assert_eq!(out.hop, Some(Hop::NoFreeSpot { radius: 0.4 }));
    assert_eq!(xz(&out.pose), Vec2::ZERO, "agent must stay put");
    assert!(out.noticeable && !out.done);
}

#[test]
fn telhop_setting_teleports_forward_moves() {
    // In the Tel-Hop setting a forward move hops over the thin wall and lands behind it.
    let scene = room_with(vec![wall(
        6,
        Vec3::new(0.0, 1.25, -1.0),
        Vec3::new(4.0, 1.25, 0.01),
    )]);
    let mut s = sim(CollisionSetting::TelHop);
    s.reset(&scene, at(0.0, 0.0, 0.0)).unwrap();
    let out = s.step(Action::MoveForward(2.0)).unwrap();
    assert_eq!(xz(&out.pose), Vec2::new(0.0, -2.0));
    assert!(!out.collided);
}

#[test]
fn turns_are_exact() {
    let mut s = sim(CollisionSetting::Strict);
    s.reset(&room(), at(0.0, 0.0, 0.0)).unwrap();
    let step = 15f32.to_radians();
    for _ in 0..24 {
        s.step(Action::TurnLeft(step)).unwrap();
    }
    let q = s.pose().rotation;
    assert!(
        (q[3].abs() - 1.0).abs() < 1e-6 && q[1].abs() < 1e-6,
        "{q:?}"
    );
    for _ in 0..24 {
        s.step(Action::TurnRight(step)).unwrap();
    }
    let q = s.pose().rotation;
    assert!(
        (q[3].abs() - 1.0).abs() < 1e-6 && q[1].abs() < 1e-6,
        "{q:?}"
    );
    // Six left turns: exactly 90 degrees.
    for _ in 0..6 {
        s.step(Action::TurnLeft(step)).unwrap();
    }
    assert!((s.pose().yaw() - FRAC_PI_2).abs() < 1e-6);
    assert_eq!(s.pose().position, [0.0; 3]);
}

fn random_actions(seed: u64, n: usize) -> Vec<Action> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| match rng.random_range(0..6) {
            0 | 1 => Action::MoveForward(0.25),
            2 => Action::TurnLeft(15f32.to_radians()),
            3 => Action::TurnRight(15f32.to_radians()),
            4 => Action::Velocity {
                v: rng.random_range(-0.5..1.0),
                omega: rng.random_range(-1.0..1.0),
                duration: 0.5,
            },
            _ => Action::Waypoint {
                x: rng.random_range(-4.0..4.0),
                z: rng.random_range(-4.0..4.0),
                mode: WaypointMode::Drive,
            },
        })
        .collect()
}

fn furnished() -> vlnverse_env::Scene {
    let mut extra = vec![];
    for i in 0..4 {
        let x = -3.0 + 2.0 * i as f32;
        extra.push(boxed(
            6 + i,
            SemanticClass::Chair,
            Vec3::new(x, 0.4, -1.5),
            Vec3::new(0.25, 0.4, 0.25),
            Motion::Dynamic,
            8.0,
            0.4,
        ));
        extra.push(boxed(
            10 + i,
            SemanticClass::Cabinet,
            Vec3::new(x, 0.5, 1.5),
            Vec3::new(0.4, 0.5, 0.3),
            Motion::Static,
            60.0,
            0.5,
        ));
    }
    room_with(extra)
}

fn run(actions: &[Action], noise: bool) -> Vec<StepOutcome> {
    let mut s = RapierSimulator::new(SimConfig {
        setting: CollisionSetting::Lenient,
        noise: noise.then(ActuationNoise::default),
        seed: 7,
        ..Default::default()
    })
    .unwrap();
    s.reset(&furnished(), at(0.0, 0.0, 0.3)).unwrap();
    actions.iter().map(|a| s.step(*a).unwrap()).collect()
}

fn bits(outs: &[StepOutcome]) -> Vec<[u32; 7]> {
    outs.iter()
        .map(|o| {
            let p = o.pose.position.map(f32::to_bits);
            let q = o.pose.rotation.map(f32::to_bits);
            [p[0], p[1], p[2], q[0], q[1], q[2], q[3]]
        })
        .collect()
}

#[test]
fn same_actions_give_bit_identical_poses() {
    let actions = random_actions(3, 120);
    for noise in [false, true] {
        let a = run(&actions, noise);
        let b = run(&actions, noise);
        assert_eq!(bits(&a), bits(&b));
        assert_eq!(a, b);
    }
    // Noise changes the result (the generator is really used).
    assert_ne!(bits(&run(&actions, false)), bits(&run(&actions, true)));
}

#[test]
fn snapshot_and_restore_reproduce_the_future() {
    let actions = random_actions(11, 80);
    let mut s = RapierSimulator::new(SimConfig {
        setting: CollisionSetting::Lenient,
        noise: Some(ActuationNoise::default()),
        ..Default::default()
    })
    .unwrap();
    s.reset(&furnished(), at(0.0, 0.0, 0.0)).unwrap();
    for a in &actions[..30] {
        s.step(*a).unwrap();
    }
    let snap = s.snapshot();
    let first: Vec<_> = actions[30..].iter().map(|a| s.step(*a).unwrap()).collect();
    let chairs: Vec<_> = (6..10).map(|id| s.object_pose(id).unwrap()).collect();
    s.restore(&snap);
    let second: Vec<_> = actions[30..].iter().map(|a| s.step(*a).unwrap()).collect();
    assert_eq!(bits(&first), bits(&second));
    assert_eq!(first, second);
    let chairs2: Vec<_> = (6..10).map(|id| s.object_pose(id).unwrap()).collect();
    assert_eq!(chairs, chairs2);
}

#[test]
fn bad_actions_give_clear_errors_and_change_nothing() {
    let mut s = sim(CollisionSetting::Strict);
    assert!(matches!(
        s.step(Action::MoveForward(0.25)),
        Err(SimError::NotReset)
    ));
    s.reset(&room(), at(0.0, 0.0, 0.0)).unwrap();
    let before = s.pose();
    let cases = [
        (Action::MoveForward(f32::NAN), "MoveForward.distance"),
        (Action::MoveForward(f32::INFINITY), "MoveForward.distance"),
        (Action::MoveForward(-0.25), "MoveForward.distance"),
        (Action::MoveForward(10.5), "MoveForward.distance"),
        (Action::TurnLeft(7.0), "TurnLeft.angle"),
        (Action::TurnRight(f32::NEG_INFINITY), "TurnRight.angle"),
        (Action::TurnRight(-0.1), "TurnRight.angle"),
        (
            Action::Velocity {
                v: 0.5,
                omega: 0.0,
                duration: 0.0,
            },
            "Velocity.duration",
        ),
        (
            Action::Velocity {
                v: 0.5,
                omega: 0.0,
                duration: 1e9,
            },
            "Velocity.duration",
        ),
        (
            Action::Velocity {
                v: f32::NAN,
                omega: 0.0,
                duration: 1.0,
            },
            "Velocity.v",
        ),
        (
            Action::Velocity {
                v: 0.0,
                omega: 1e6,
                duration: 1.0,
            },
            "Velocity.omega",
        ),
        (
            Action::Waypoint {
                x: 50.0,
                z: 0.0,
                mode: WaypointMode::Drive,
            },
            "outside the scene",
        ),
        (
            Action::Waypoint {
                x: f32::NAN,
                z: 0.0,
                mode: WaypointMode::TelHop,
            },
            "Waypoint.x",
        ),
    ];
    for (a, needle) in cases {
        let e = s.step(a).unwrap_err().to_string();
        assert!(e.contains(needle), "{a:?}: {e}");
    }
    // The message names the value too.
    let e = s
        .step(Action::MoveForward(f32::NAN))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("MoveForward.distance") && e.contains("NaN"),
        "{e}"
    );
    assert_eq!(s.pose(), before);
    assert!(s.step(Action::Stop).unwrap().failure.is_none());
    assert!(matches!(
        s.step(Action::MoveForward(0.25)),
        Err(SimError::EpisodeOver(_))
    ));
}

#[test]
fn strict_fails_at_the_first_noticeable_collision_lenient_only_counts() {
    // 0.5 m from the wall (surface to surface), 1 m forward: 0.5 m short -> noticeable.
    let start = at(0.0, -5.0 + 0.3 + 0.5, 0.0);
    let mut strict = sim(CollisionSetting::Strict);
    strict.reset(&room(), start).unwrap();
    let ok = strict.step(Action::MoveForward(0.25)).unwrap();
    assert!(!ok.collided && !ok.done);
    let out = strict.step(Action::MoveForward(1.0)).unwrap();
    assert!(out.noticeable && out.done);
    assert_eq!(out.failure, Some(Failure::Collision { hit: vec![2] }));
    assert!(strict.step(Action::TurnLeft(0.1)).is_err());

    let mut lenient = sim(CollisionSetting::Lenient);
    lenient.reset(&room(), start).unwrap();
    lenient.step(Action::MoveForward(0.25)).unwrap();
    let out = lenient.step(Action::MoveForward(1.0)).unwrap();
    assert!(out.noticeable && !out.done && out.failure.is_none());
    // A graze below the threshold is a collision but not a noticeable one.
    lenient
        .reset(&room(), at(0.0, -5.0 + 0.3 + 0.05, 0.0))
        .unwrap();
    let out = lenient.step(Action::MoveForward(0.1)).unwrap();
    assert!(out.collided && !out.noticeable, "{out:?}");
}

#[test]
fn look_up_and_down_tilt_the_camera_within_limits() {
    let mut s = sim(CollisionSetting::Strict);
    s.reset(&room(), at(1.0, 2.0, 0.0)).unwrap();
    let cam = s.camera_pose();
    assert_eq!(cam.position, [1.0, 1.25, 2.0]);
    for _ in 0..5 {
        s.step(Action::LookUp).unwrap();
    }
    let fwd = s.camera_pose().quat() * Vec3::NEG_Z;
    // Clamped at 60 degrees up.
    assert!((fwd.y - 60f32.to_radians().sin()).abs() < 1e-5, "{fwd}");
    s.step(Action::LookDown).unwrap();
    let fwd = s.camera_pose().quat() * Vec3::NEG_Z;
    assert!((fwd.y - 30f32.to_radians().sin()).abs() < 1e-5, "{fwd}");
    assert_eq!(s.pose().position, [1.0, 0.0, 2.0]);
}

#[test]
fn differential_drive_limits_speed_and_turn_rate() {
    let agent = AgentConfig::profile("locobot").unwrap();
    let mut s = RapierSimulator::new(SimConfig {
        agent,
        setting: CollisionSetting::Lenient,
        ..Default::default()
    })
    .unwrap();
    s.reset(&room(), at(0.0, 0.0, 0.0)).unwrap();
    // Full speed and full turn at once: wheels saturate, both are scaled down.
    let out = s
        .step(Action::Velocity {
            v: 0.7,
            omega: 3.0,
            duration: 2.0,
        })
        .unwrap();
    let travelled = Vec2::from(out.achieved).length();
    assert!(travelled < 0.7 * 2.0 * 0.8, "travelled {travelled}");
    assert!(travelled > 0.2, "travelled {travelled}");
}

#[test]
fn driven_waypoint_turns_and_moves_with_collisions() {
    let mut s = sim(CollisionSetting::Lenient);
    s.reset(&table_scene(), at(0.0, 0.0, 0.0)).unwrap();
    let out = s
        .step(Action::Waypoint {
            x: 4.0,
            z: 0.0,
            mode: WaypointMode::Drive,
        })
        .unwrap();
    // The table (x in [1.5, 2.5]) blocks the straight line: stops at 1.5 - 0.3.
    assert!(out.collided && out.hit == vec![6], "{out:?}");
    assert!(out.pose.position[0] <= 1.2 + 1e-3 && out.pose.position[0] > 1.1);
    assert!((out.pose.yaw() + FRAC_PI_2).abs() < 1e-5); // facing +x
}

#[test]
fn vec_simulator_matches_single_environments() {
    let scene = furnished();
    let n = 6;
    let cfg = SimConfig {
        setting: CollisionSetting::Lenient,
        ..Default::default()
    };
    let mut v = VecSimulator::new(n, cfg.clone(), Some(2)).unwrap();
    let starts: Vec<_> = (0..n)
        .map(|i| at(-2.0 + 0.8 * i as f32, 0.0, 0.2 * i as f32))
        .collect();
    v.reset_all(&scene, &starts).unwrap();
    let seqs: Vec<_> = (0..n).map(|i| random_actions(100 + i as u64, 40)).collect();
    let mut batched = vec![vec![]; n];
    for t in 0..40 {
        let acts: Vec<_> = seqs.iter().map(|s| s[t]).collect();
        for (i, r) in v.step(&acts).unwrap().into_iter().enumerate() {
            batched[i].push(r.unwrap());
        }
    }
    for i in 0..n {
        let mut s = RapierSimulator::new(cfg.clone()).unwrap();
        s.reset(&scene, starts[i]).unwrap();
        let single: Vec<_> = seqs[i].iter().map(|a| s.step(*a).unwrap()).collect();
        assert_eq!(bits(&single), bits(&batched[i]), "env {i}");
    }
    assert!(
        v.step(&[Action::Stop]).is_err(),
        "wrong batch size must error"
    );
}

#[test]
fn box_agent_cannot_turn_into_a_wall() {
    let mut cfg = SimConfig {
        setting: CollisionSetting::Lenient,
        ..Default::default()
    };
    cfg.agent.shape = AgentShape::Box {
        height: 1.0,
        width: 0.4,
        length: 1.6,
    };
    let mut s = RapierSimulator::new(cfg).unwrap();
    // Long axis along z, 0.35 m from the +x wall: turning 90 degrees would put it into the wall.
    s.reset(&room(), at(5.0 - 0.35, 0.0, 0.0)).unwrap();
    let out = s.step(Action::TurnLeft(FRAC_PI_2)).unwrap();
    assert!(out.collided && out.hit.contains(&5), "{out:?}");
    assert!(s.pose().yaw().abs() < 1e-6);
}

#[test]
fn every_profile_drives_over_a_rug_lower_than_its_ground_clearance() {
    // A 12 mm rug (as procgen makes them) across the path, static and light dynamic versions.
    for motion in [Motion::Static, Motion::Dynamic] {
        let rug = boxed(
            6,
            SemanticClass::Rug,
            Vec3::new(0.0, 0.006, -1.5),
            Vec3::new(1.5, 0.006, 1.0),
            motion,
            3.0,
            0.8,
        );
        let scene = room_with(vec![rug]);
        for profile in ["vlnverse", "vlnce", "rxr", "locobot"] {
            let agent = AgentConfig::profile(profile).unwrap();
            assert!(agent.ground_clearance > 0.012, "{profile}");
            let mut s = RapierSimulator::new(SimConfig {
                agent: agent.clone(),
                setting: CollisionSetting::Strict,
                ..Default::default()
            })
            .unwrap();
            // Velocity control: 4 m straight ahead (-Z) across the rug.
            s.reset(&scene, at(0.0, 1.0, 0.0)).unwrap();
            let v = 0.5 * agent.max_linear_speed;
            let mut hit = Vec::new();
            while s.pose().position[2] > -3.0 {
                let out = s
                    .step(Action::Velocity {
                        v,
                        omega: 0.0,
                        duration: 0.5,
                    })
                    .unwrap();
                assert!(!out.done, "{profile} {motion:?}: stopped: {out:?}");
                hit.extend(out.hit);
            }
            assert!(
                hit.is_empty(),
                "{profile} {motion:?} velocity: touched {hit:?}"
            );
            // Discrete moves over the same rug.
            s.reset(&scene, at(0.0, 1.0, 0.0)).unwrap();
            for _ in 0..16 {
                let out = s.step(Action::MoveForward(0.25)).unwrap();
                assert!(
                    !out.noticeable && out.hit.is_empty(),
                    "{profile} {motion:?}: {out:?}"
                );
            }
        }
    }
}
