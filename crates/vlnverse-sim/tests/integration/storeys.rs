//! The agent in homes on two floors (docs/storeys.md): it climbs a generated flight in Strict
//! and hops up it in Tel-Hop, an agent whose step is lower than the rise stays at the foot,
//! the camera follows it upstairs, and in a hand-made two-level scene it steps onto a low
//! platform and falls off a slab's edge.

use glam::Vec3;
use std::sync::Arc;
use vlnverse_env::{Level, Motion, Pose, Scene, SceneSource, SemanticClass, Stairs, Storeys};
use vlnverse_procgen::{HomeGenerator, ProcgenConfig};
use vlnverse_sensors::{Camera, Channels, Renderer, SceneMesh, View};
use vlnverse_sim::*;

use crate::common::{boxed, room_with};

/// The first `n` two-storey homes of `configs/scenes/two_storey.toml` (seed 2026).
fn two_storey_homes(n: usize) -> Vec<Scene> {
    let cfg = ProcgenConfig::from_toml_str(
        include_str!("../../../vlnverse-procgen/configs/scenes/two_storey.toml"),
        None,
    )
    .unwrap();
    let g = HomeGenerator::new(cfg).unwrap();
    (0..g.len())
        .map(|i| g.scene(i).unwrap())
        .filter(|s| s.is_multi_level())
        .take(n)
        .collect()
}

/// The start at a flight's foot facing its head, and the horizontal distance to the head.
fn at_foot(st: &Stairs) -> (Pose, f32) {
    let (f, h) = (Vec3::from(st.foot), Vec3::from(st.head));
    let d = Vec3::new(h.x - f.x, 0.0, h.z - f.z);
    // Yaw 0 looks along -Z; yaw turns counter-clockwise seen from above.
    let yaw = (-d.x).atan2(-d.z);
    (Pose::from_yaw(f, yaw), d.length())
}

fn sim(setting: CollisionSetting, max_step_height: f32) -> RapierSimulator {
    RapierSimulator::new(SimConfig {
        setting,
        agent: AgentConfig {
            max_step_height,
            ..Default::default()
        },
        ..Default::default()
    })
    .unwrap()
}

/// Step forward from the foot until the head is less than half a step away or the episode
/// ends; the outcomes.
fn walk_up(sim: &mut RapierSimulator, scene: &Scene, st: &Stairs) -> Vec<StepOutcome> {
    let (start, length) = at_foot(st);
    sim.reset(scene, start).unwrap();
    let step = sim.config().agent.step_size;
    let n = (length / step).round() as usize;
    let mut outs = Vec::new();
    for _ in 0..n {
        let out = sim.step(Action::MoveForward(step)).unwrap();
        let done = out.done;
        outs.push(out);
        if done {
            break;
        }
    }
    outs
}

fn horizontal(a: [f32; 3], b: [f32; 3]) -> f32 {
    (a[0] - b[0]).hypot(a[2] - b[2])
}

#[test]
fn strict_agent_walks_up_and_down_a_generated_flight() {
    for scene in two_storey_homes(3) {
        let st = &scene.storeys.stairs[0];
        let upper = scene.level_height(st.levels[1]).unwrap();
        let mut sim = sim(CollisionSetting::Strict, DEFAULT_MAX_STEP);
        let outs = walk_up(&mut sim, &scene, st);
        assert!(
            outs.iter().all(|o| o.failure.is_none() && !o.noticeable),
            "{}: {:?}",
            scene.id,
            outs.iter().find(|o| o.failure.is_some())
        );
        // Up the flight one tread at a time: never more than a step per move, never down.
        let mut y = scene.floor_height;
        for o in &outs {
            let dy = o.pose.position[1] - y;
            assert!((-1e-4..=st.rise + 1e-3).contains(&dy), "{}: {dy}", scene.id);
            y = o.pose.position[1];
        }
        let end = sim.pose().position;
        assert_eq!(end[1], upper, "{}: ends at {end:?}", scene.id);
        assert!(horizontal(end, st.head) < 0.2, "{}: {end:?}", scene.id);
        // The camera is at the sensor height above the upper floor.
        let cam = sim.camera_pose().position;
        assert!((cam[1] - upper - sim.config().agent.sensor_height).abs() < 1e-5);

        // And back down: turn round and walk to the foot.
        sim.step(Action::TurnLeft(std::f32::consts::PI)).unwrap();
        let n = (at_foot(st).1 / 0.25).round() as usize;
        for _ in 0..n {
            let out = sim.step(Action::MoveForward(0.25)).unwrap();
            assert!(out.failure.is_none(), "{}: {out:?}", scene.id);
        }
        let end = sim.pose().position;
        assert_eq!(end[1], scene.floor_height, "{}: back at {end:?}", scene.id);
        assert!(horizontal(end, st.foot) < 0.2, "{}: {end:?}", scene.id);
    }
}

/// The default step of the profile (a constant so the tests say which they use).
const DEFAULT_MAX_STEP: f32 = vlnverse_sim::config::DEFAULT_MAX_STEP_HEIGHT;

#[test]
fn an_agent_with_a_step_lower_than_the_rise_stays_at_the_foot() {
    for scene in two_storey_homes(2) {
        let st = &scene.storeys.stairs[0];
        let mut strict = sim(CollisionSetting::Strict, 0.1);
        let outs = walk_up(&mut strict, &scene, st);
        let last = outs.last().unwrap();
        assert!(
            matches!(last.failure, Some(Failure::Collision { .. })),
            "{}: {last:?}",
            scene.id
        );
        assert_eq!(
            strict.pose().position[1],
            scene.floor_height,
            "{}",
            scene.id
        );
        // Stopped by the first riser, within a step of the foot.
        assert!(horizontal(strict.pose().position, st.foot) < 1.0 + 0.25);

        let mut hop = sim(CollisionSetting::TelHop, 0.1);
        walk_up(&mut hop, &scene, st);
        assert_eq!(hop.pose().position[1], scene.floor_height, "{}", scene.id);
        hop.reset(&scene, at_foot(st).0).unwrap();
        hop.step(Action::Waypoint {
            x: st.head[0],
            z: st.head[2],
            mode: WaypointMode::TelHop,
        })
        .unwrap();
        assert_eq!(hop.pose().position[1], scene.floor_height, "{}", scene.id);
    }
}

#[test]
fn tel_hop_climbs_by_moves_and_by_one_waypoint_to_the_head() {
    for scene in two_storey_homes(3) {
        let st = &scene.storeys.stairs[0];
        let upper = scene.level_height(st.levels[1]).unwrap();
        let mut sim = sim(CollisionSetting::TelHop, DEFAULT_MAX_STEP);
        let outs = walk_up(&mut sim, &scene, st);
        assert!(outs.iter().all(|o| !o.noticeable), "{}: {outs:?}", scene.id);
        assert_eq!(sim.pose().position[1], upper, "{}", scene.id);

        // One waypoint from the foot to the head lands upstairs, next to the head.
        sim.reset(&scene, at_foot(st).0).unwrap();
        let out = sim
            .step(Action::Waypoint {
                x: st.head[0],
                z: st.head[2],
                mode: WaypointMode::TelHop,
            })
            .unwrap();
        assert!(
            matches!(out.hop, Some(Hop::Landed { shift }) if shift < 0.3),
            "{}: {out:?}",
            scene.id
        );
        assert_eq!(sim.pose().position[1], upper, "{}", scene.id);
        // And one back to the foot lands downstairs.
        sim.step(Action::Waypoint {
            x: st.foot[0],
            z: st.foot[2],
            mode: WaypointMode::TelHop,
        })
        .unwrap();
        assert_eq!(sim.pose().position[1], scene.floor_height, "{}", scene.id);
    }
}

#[test]
fn a_reset_upstairs_stands_on_the_upper_floor_and_sees_it_in_depth() {
    let scene = &two_storey_homes(1)[0];
    let st = &scene.storeys.stairs[0];
    let upper = scene.level_height(1).unwrap();
    let mut sim = sim(CollisionSetting::Strict, DEFAULT_MAX_STEP);
    // Reset at the head, a hair above the floor: the agent stands on the slab.
    let (foot, _) = at_foot(st);
    let head = Pose {
        position: [st.head[0], upper + 0.01, st.head[2]],
        rotation: foot.rotation,
    };
    sim.reset(scene, head).unwrap();
    assert_eq!(sim.pose().position[1], upper);
    assert!(sim.is_free(st.head[0], st.head[2]));
    // Look down 60 degrees: the centre ray meets the upper floor at sensor_height / sin 60,
    // unless something on the floor is nearer (never the ground floor, 2.8 m further down).
    sim.step(Action::LookDown).unwrap();
    sim.step(Action::LookDown).unwrap();
    let cam = sim.camera_pose();
    let h = sim.config().agent.sensor_height;
    assert!((cam.position[1] - (upper + h)).abs() < 1e-5);
    let mut r = vlnverse_sensors::RaycastRenderer::new();
    r.set_scene(Arc::new(SceneMesh::new(scene).unwrap()))
        .unwrap();
    let camera = Camera::new(&cam, 33, 33, 90f32.to_radians(), 0.05, 20.0);
    let frame = r
        .render(&[View {
            camera,
            channels: Channels::DEPTH,
        }])
        .unwrap()
        .remove(0);
    assert!(frame.depth.iter().all(|d| d.is_finite() && *d > 0.0));
    let centre = frame.depth[frame.index(16, 16)];
    let floor = h / 60f32.to_radians().sin();
    assert!(
        centre > 0.1 && centre < floor + 0.05,
        "centre depth {centre}, the floor is {floor} away"
    );
}

/// A 10 m room with a second level: a 1 m high slab over `x > 1` (class floor, level 1) and a
/// 0.15 m platform at `x` in [-3, -2] on the ground floor.
fn two_level_room() -> Scene {
    let mut s = room_with(vec![
        boxed(
            6,
            SemanticClass::Floor,
            Vec3::new(3.0, 0.9, 0.0),
            Vec3::new(2.0, 0.1, 5.0),
            Motion::Static,
            1000.0,
            0.6,
        ),
        boxed(
            7,
            SemanticClass::Bed,
            Vec3::new(-2.5, 0.075, 0.0),
            Vec3::new(0.5, 0.075, 5.0),
            Motion::Static,
            1000.0,
            0.6,
        ),
    ]);
    s.storeys = Storeys {
        levels: vec![
            Level {
                id: 0,
                name: "ground floor".into(),
                floor_height: 0.0,
                rooms: vec![],
            },
            Level {
                id: 1,
                name: "upper floor".into(),
                floor_height: 1.0,
                rooms: vec![],
            },
        ],
        stairs: vec![],
    };
    s
}

#[test]
fn steps_onto_a_low_platform_and_falls_off_a_slab_edge() {
    let scene = two_level_room();
    // Facing -x (yaw +90 degrees): onto the 0.15 m platform and off it again.
    let mut strict = sim(CollisionSetting::Strict, DEFAULT_MAX_STEP);
    strict
        .reset(
            &scene,
            Pose::from_yaw(Vec3::new(-0.5, 0.0, 0.0), 90f32.to_radians()),
        )
        .unwrap();
    let out = strict.step(Action::MoveForward(2.0)).unwrap();
    assert!(out.failure.is_none(), "{out:?}");
    assert!((strict.pose().position[1] - 0.15).abs() < 1e-3, "{out:?}");
    strict.step(Action::MoveForward(1.5)).unwrap();
    assert_eq!(strict.pose().position[1], 0.0);

    // A lower step height: the platform is a wall.
    let mut low = sim(CollisionSetting::Strict, 0.1);
    low.reset(
        &scene,
        Pose::from_yaw(Vec3::new(-0.5, 0.0, 0.0), 90f32.to_radians()),
    )
    .unwrap();
    let out = low.step(Action::MoveForward(2.0)).unwrap();
    assert!(out.failure.is_some(), "{out:?}");
    assert_eq!(low.pose().position[1], 0.0);

    // On the slab (reset on level 1), walking off its edge at x = 1 falls to the floor.
    let mut up = sim(CollisionSetting::Lenient, DEFAULT_MAX_STEP);
    up.reset(
        &scene,
        Pose::from_yaw(Vec3::new(3.0, 1.0, 0.0), 90f32.to_radians()),
    )
    .unwrap();
    assert_eq!(up.pose().position[1], 1.0);
    up.step(Action::MoveForward(1.0)).unwrap();
    assert_eq!(up.pose().position[1], 1.0, "still over the slab");
    let out = up.step(Action::MoveForward(1.5)).unwrap();
    assert_eq!(up.pose().position[1], 0.0, "{out:?}");
    // The 1 m edge cannot be climbed back: the move stops at it.
    let mut back = sim(CollisionSetting::Strict, DEFAULT_MAX_STEP);
    back.reset(
        &scene,
        Pose::from_yaw(Vec3::new(0.0, 0.0, 0.0), -90f32.to_radians()),
    )
    .unwrap();
    let out = back.step(Action::MoveForward(2.0)).unwrap();
    assert!(out.failure.is_some(), "{out:?}");
    assert_eq!(back.pose().position[1], 0.0);
}

#[test]
fn a_walk_in_a_two_storey_home_is_deterministic() {
    let scene = &two_storey_homes(1)[0];
    let st = &scene.storeys.stairs[0];
    let run = || {
        let mut s = sim(CollisionSetting::Lenient, DEFAULT_MAX_STEP);
        walk_up(&mut s, scene, st)
            .iter()
            .map(|o| o.pose.position.map(f32::to_bits))
            .collect::<Vec<_>>()
    };
    assert_eq!(run(), run());
}

/// Drive straight ahead at `v` m/s for `seconds`, from `start` (reset) when given.
fn drive(
    sim: &mut RapierSimulator,
    scene: &Scene,
    start: Option<Pose>,
    v: f32,
    seconds: f32,
) -> StepOutcome {
    if let Some(p) = start {
        sim.reset(scene, p).unwrap();
    }
    sim.step(Action::Velocity {
        v,
        omega: 0.0,
        duration: seconds,
    })
    .unwrap()
}

#[test]
fn velocity_control_falls_off_an_edge_and_steps_onto_a_low_platform() {
    let scene = two_level_room();
    let facing_x = |x: f32, y: f32| Some(Pose::from_yaw(Vec3::new(x, y, 0.0), 90f32.to_radians()));
    let mut s = sim(CollisionSetting::Lenient, DEFAULT_MAX_STEP);
    // On the slab facing its edge at x = 1: 2.5 s at 1 m/s goes over it.
    drive(&mut s, &scene, facing_x(3.0, 1.0), 1.0, 3.0);
    let p = s.pose().position;
    assert!(p[0] < 0.7, "{p:?}");
    assert_eq!(p[1], 0.0, "{p:?}");
    // Facing the 0.15 m platform (within the 0.2 m step): it walks up onto it.
    drive(&mut s, &scene, facing_x(-0.5, 0.0), 1.0, 2.0);
    let p = s.pose().position;
    assert!((p[1] - 0.15).abs() < 1e-3 && p[0] < -2.0, "{p:?}");
    // An agent whose step is lower than the platform is stopped at its edge.
    let mut low = sim(CollisionSetting::Lenient, 0.1);
    let out = drive(&mut low, &scene, facing_x(-0.5, 0.0), 1.0, 3.0);
    let p = low.pose().position;
    assert!(out.collided, "{out:?}");
    assert!(p[1] == 0.0 && p[0] > -2.0, "{p:?}");
}

#[test]
fn velocity_control_walks_up_a_generated_flight() {
    for scene in two_storey_homes(3) {
        let st = &scene.storeys.stairs[0];
        let upper = scene.level_height(st.levels[1]).unwrap();
        let (start, length) = at_foot(st);
        let mut s = sim(CollisionSetting::Strict, DEFAULT_MAX_STEP);
        // 0.5 m/s for as long as the walk takes, in steps of a quarter second.
        let ticks = (length / 0.5 / 0.25).ceil() as usize;
        for k in 0..ticks {
            drive(&mut s, &scene, (k == 0).then_some(start), 0.5, 0.25);
        }
        let p = s.pose().position;
        assert!(
            (p[1] - upper).abs() < 1e-3,
            "{}: stopped at {p:?}",
            scene.id
        );
        assert!(horizontal(p, st.head) < 0.6, "{}: {p:?}", scene.id);
    }
}

#[test]
fn the_agent_stands_on_floors_and_steps_never_on_furniture() {
    // A 0.15 m platform (a step) at x in [-3, -2] and, behind it, a 0.3 m sofa at x in
    // [-4, -3]: its top is within a step of the platform's, but it is furniture.
    let mut scene = two_level_room();
    scene.objects.push(boxed(
        8,
        SemanticClass::Sofa,
        Vec3::new(-3.5, 0.15, 0.0),
        Vec3::new(0.5, 0.15, 5.0),
        Motion::Static,
        1000.0,
        0.6,
    ));
    let mut sim = sim(CollisionSetting::Lenient, DEFAULT_MAX_STEP);
    sim.reset(
        &scene,
        Pose::from_yaw(Vec3::new(-0.5, 0.0, 0.0), 90f32.to_radians()),
    )
    .unwrap();
    sim.step(Action::MoveForward(2.0)).unwrap();
    assert!((sim.pose().position[1] - 0.15).abs() < 1e-3);
    let out = sim.step(Action::MoveForward(1.0)).unwrap();
    assert!(out.noticeable && out.hit.contains(&8), "{out:?}");
    assert!((sim.pose().position[1] - 0.15).abs() < 1e-3);
    assert!(sim.pose().position[0] > -3.0 + 0.29, "{out:?}");
}
