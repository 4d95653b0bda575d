//! Closed doors in a generated home block the agent in every setting: Strict moves stop at the
//! leaf (a static collider), Tel-Hop hops never land behind it; open doors let it through.

use glam::{Vec2, Vec3};
use vlnverse_env::{Door, DoorState, Pose, Scene, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sim::*;

/// The first vlnverse home with a closed door, and that door.
fn home_with_closed_door() -> (Scene, Door) {
    let g = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
    (0..g.len())
        .find_map(|i| {
            let s = g.scene(i).unwrap();
            let d = s.doors.iter().find(|d| d.is_closed())?.clone();
            Some((s, d))
        })
        .expect("the preset has a closed door")
}

fn sim(setting: CollisionSetting) -> RapierSimulator {
    RapierSimulator::new(SimConfig {
        setting,
        ..Default::default()
    })
    .unwrap()
}

fn centre_normal(d: &Door) -> (Vec2, Vec2) {
    (
        Vec2::new(d.position[0], d.position[2]),
        Vec2::from_array(d.normal),
    )
}

/// Standing `dist` in front of door `d` on the side `n` points to, on the door's floor, facing
/// it.
fn facing(d: &Door, c: Vec2, n: Vec2, dist: f32) -> Pose {
    let p = c + n * dist;
    let yaw = (n.x).atan2(n.y);
    Pose::from_yaw(Vec3::new(p.x, d.position[1], p.y), yaw)
}

/// Signed distance of the agent from the wall line, along `n`.
fn side(out: &StepOutcome, c: Vec2, n: Vec2) -> f32 {
    (Vec2::new(out.pose.position[0], out.pose.position[2]) - c).dot(n)
}

#[test]
fn a_strict_agent_driving_at_a_closed_door_stops_at_it() {
    let (scene, d) = home_with_closed_door();
    let (c, n) = centre_normal(&d);
    for sign in [1.0, -1.0] {
        let n = n * sign;
        let mut s = sim(CollisionSetting::Strict);
        s.reset(&scene, facing(&d, c, n, 1.0)).unwrap();
        let mut stopped = false;
        for _ in 0..12 {
            let out = s.step(Action::MoveForward(0.25)).unwrap();
            assert!(
                side(&out, c, n) > 0.25,
                "{}: through door {}",
                scene.id,
                d.id
            );
            if out.done {
                assert!(matches!(out.failure, Some(Failure::Collision { .. })));
                assert!(out.hit.contains(&d.leaf.unwrap()), "{out:?}");
                stopped = true;
                break;
            }
        }
        assert!(
            stopped,
            "{}: the strict episode did not end at door {}",
            scene.id, d.id
        );
    }
}

#[test]
fn a_telhop_never_passes_a_closed_door() {
    let (scene, d) = home_with_closed_door();
    let (c, n) = centre_normal(&d);
    let mut s = sim(CollisionSetting::TelHop);
    s.reset(&scene, facing(&d, c, n, 0.6)).unwrap();
    // A waypoint well behind the door (farther than the hop search reaches back to this
    // side): refused, the agent stays.
    let far = c - n * 1.5;
    let out = s
        .step(Action::Waypoint {
            x: far.x,
            z: far.y,
            mode: WaypointMode::TelHop,
        })
        .unwrap();
    assert_eq!(out.hop, Some(Hop::ClosedDoor { door: d.id }), "{out:?}");
    assert!(out.noticeable && out.collided && !out.done);
    assert!((side(&out, c, n) - 0.6).abs() < 1e-4);
    // Just behind it: the hop lands at the nearest free spot on this side.
    let near = c - n * 0.6;
    let out = s
        .step(Action::Waypoint {
            x: near.x,
            z: near.y,
            mode: WaypointMode::TelHop,
        })
        .unwrap();
    assert!(matches!(out.hop, Some(Hop::Landed { .. })), "{out:?}");
    assert!(side(&out, c, n) > 0.3, "{out:?}");
    // Forward hops into the leaf land on this side.
    s.reset(&scene, facing(&d, c, n, 0.6)).unwrap();
    for _ in 0..8 {
        let out = s.step(Action::MoveForward(0.25)).unwrap();
        assert!(side(&out, c, n) > 0.0, "{out:?}");
    }
}

#[test]
fn an_open_door_lets_the_agent_through() {
    let g = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let scene = g.scene(0).unwrap();
    let d = scene
        .doors
        .iter()
        .find(|d| d.state == Some(DoorState::Open))
        .expect("an open door")
        .clone();
    let (c, n) = centre_normal(&d);
    let mut s = sim(CollisionSetting::Strict);
    s.reset(&scene, facing(&d, c, n, 1.0)).unwrap();
    // Through and on to 0.5 m past the wall: the clearance box (1 m deep) is free.
    let mut last = 1.0;
    for _ in 0..6 {
        let out = s.step(Action::MoveForward(0.25)).unwrap();
        assert!(!out.done, "{out:?}");
        last = side(&out, c, n);
    }
    assert!(last < -0.45, "still at {last} m from the wall");
    let mut t = sim(CollisionSetting::TelHop);
    t.reset(&scene, facing(&d, c, n, 0.6)).unwrap();
    let to = c - n * 0.6;
    let out = t
        .step(Action::Waypoint {
            x: to.x,
            z: to.y,
            mode: WaypointMode::TelHop,
        })
        .unwrap();
    assert!(matches!(out.hop, Some(Hop::Landed { .. })), "{out:?}");
    assert!(side(&out, c, n) < -0.5);
}
