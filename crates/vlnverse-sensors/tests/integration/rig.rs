//! The sensor rig: configs, rates, panoramas, LiDAR, pose sensors, noise.

use crate::common;

use glam::Vec3;
use std::sync::Arc;
use vlnverse_env::Pose;
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::{
    AgentState, Backend, CameraSpec, Channels, CollisionInfo, LidarSpec, Noise, Observation,
    PanoramaSpec, Rate, RaycastRenderer, Renderer, RigConfig, SceneMesh, SceneRaycaster, SensorRig,
    SensorSpec, StateSpec, View,
};

fn raycast_rig(sensors: Vec<SensorSpec>) -> SensorRig {
    let mut rig = SensorRig::new(RigConfig {
        backend: Backend::Raycast,
        seed: 7,
        sensors,
    })
    .unwrap();
    rig.set_scene(&demo_scene(1)).unwrap();
    rig
}

#[test]
fn shipped_configs_load_and_validate() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/sensors");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    for want in ["default.toml", "vlnce.toml", "full.toml", "lidar.toml"] {
        assert!(names.iter().any(|p| p.ends_with(want)), "missing {want}");
    }
    for p in &names {
        let c = RigConfig::load(p).unwrap_or_else(|e| panic!("{e}"));
        assert!(!c.sensors.is_empty(), "{}", p.display());
    }
    // default.toml is the paper's rig.
    assert_eq!(
        RigConfig::load(dir.join("default.toml")).unwrap().sensors,
        RigConfig::default().sensors
    );
    // Every file is embedded (and nothing else), and the embedded text is the file's.
    let embedded: Vec<&str> = vlnverse_sensors::config::SHIPPED_RIGS
        .iter()
        .map(|(n, _)| *n)
        .collect();
    let stems: Vec<String> = names
        .iter()
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(stems, embedded);
    for (name, text) in vlnverse_sensors::config::SHIPPED_RIGS {
        let file = std::fs::read_to_string(dir.join(format!("{name}.toml"))).unwrap();
        assert_eq!(file, text, "{name}");
    }
    // The repository's user-facing `configs/sensors/` (a link to the crate's folder, as for
    // `configs/agent` and `configs/scenes`) holds the same files.
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/sensors");
    if root.exists() {
        for (name, text) in vlnverse_sensors::config::SHIPPED_RIGS {
            let file = std::fs::read_to_string(root.join(format!("{name}.toml"))).unwrap();
            assert_eq!(file, text, "configs/sensors/{name}.toml");
        }
    }
}

#[test]
fn default_rig_gives_rgb_224_and_depth_256_clipped_at_10m() {
    let mut rig = raycast_rig(RigConfig::default().sensors);
    let obs = rig
        .observe(&AgentState::at(Vec3::new(3.5, 0.0, 4.0), 0.7))
        .unwrap();
    match &obs["rgb"] {
        Observation::Rgb(f) => {
            assert_eq!((f.width, f.height, f.rgb.len()), (224, 224, 224 * 224 * 3))
        }
        o => panic!("{o:?}"),
    }
    match &obs["depth"] {
        Observation::Depth(f) => {
            assert_eq!((f.width, f.height, f.depth.len()), (256, 256, 256 * 256));
            // Clipped at 10 m and normalised: 1.0 is "10 m or more".
            assert!(f.depth.iter().all(|d| (0.0..=1.0).contains(d)));
            assert!(f.depth.iter().any(|d| *d > 0.0 && *d < 1.0));
        }
        o => panic!("{o:?}"),
    }
}

#[test]
fn normalised_depth_is_depth_over_far() {
    // The default depth camera normalises (the paper); metres are one field away.
    assert!(CameraSpec::depth().normalize);
    let plain = CameraSpec {
        normalize: false,
        ..CameraSpec::depth()
    };
    let norm = CameraSpec {
        name: "depth_n".into(),
        normalize: true,
        far: 4.0,
        ..CameraSpec::depth()
    };
    let mut rig = raycast_rig(vec![SensorSpec::Depth(plain), SensorSpec::Depth(norm)]);
    let obs = rig
        .observe(&AgentState::at(Vec3::new(3.5, 0.0, 4.0), 2.0))
        .unwrap();
    let (Observation::Depth(a), Observation::Depth(b)) = (&obs["depth"], &obs["depth_n"]) else {
        panic!()
    };
    for (x, y) in a.depth.iter().zip(&b.depth) {
        assert!((x.min(4.0) / 4.0 - y).abs() < 1e-5, "{x} {y}");
    }
    assert!(b.depth.contains(&1.0), "something beyond 4 m is clipped");
}

#[test]
fn rates_every_k_steps_and_hz() {
    let every2 = SensorSpec::Pose(StateSpec {
        name: "pose2".into(),
        rate: Rate {
            every_steps: 2,
            hz: None,
        },
    });
    let hz = SensorSpec::Compass(StateSpec {
        name: "compass5hz".into(),
        rate: Rate {
            every_steps: 1,
            hz: Some(5.0),
        },
    });
    let mut rig = raycast_rig(vec![every2, hz]);
    let mut seen = Vec::new();
    for step in 0..8u64 {
        let mut s = AgentState::at(Vec3::new(3.5, 0.0, 4.0), 0.0);
        s.step = step;
        s.time_s = step as f64 * 0.1; // 10 Hz simulation
        let o = rig.observe(&s).unwrap();
        seen.push((o.contains_key("pose2"), o.contains_key("compass5hz")));
    }
    let pose: Vec<bool> = seen.iter().map(|s| s.0).collect();
    let comp: Vec<bool> = seen.iter().map(|s| s.1).collect();
    assert_eq!(pose, [true, false, true, false, true, false, true, false]);
    assert_eq!(comp, [true, false, true, false, true, false, true, false]);
}

#[test]
fn attach_and_detach() {
    let mut rig = raycast_rig(vec![]);
    let s = AgentState::at(Vec3::new(3.5, 0.0, 4.0), 0.0);
    assert!(rig.observe(&s).unwrap().is_empty());
    rig.attach(SensorSpec::Semantic(CameraSpec::default()))
        .unwrap();
    assert!(
        rig.attach(SensorSpec::Semantic(CameraSpec::default()))
            .is_err(),
        "duplicate name"
    );
    let bad = SensorSpec::Rgb(CameraSpec {
        width: 0,
        ..CameraSpec::default()
    });
    assert!(rig.attach(bad).unwrap_err().to_string().contains("width"));
    let o = rig.observe(&s).unwrap();
    assert!(
        matches!(&o["semantic"], Observation::Semantic(f) if f.semantic.iter().any(|c| *c != 0))
    );
    assert!(rig.detach("semantic").is_some());
    assert!(rig.detach("semantic").is_none());
    assert!(rig.observe(&s).unwrap().is_empty());
}

#[test]
fn compass_gps_pose_and_collision() {
    let specs = ["pose", "compass", "gps", "collision"]
        .map(|k| toml::from_str::<SensorSpec>(&format!("type = \"{k}\"")).unwrap());
    let mut rig = raycast_rig(specs.to_vec());
    rig.reset(Pose::from_yaw(
        Vec3::new(1.0, 0.0, 1.0),
        std::f32::consts::FRAC_PI_2,
    ));
    let mut s = AgentState::at(Vec3::new(0.0, 0.0, 1.0), std::f32::consts::PI);
    s.collision = CollisionInfo {
        collided: true,
        displacement: 0.12,
        count: 3,
    };
    let o = rig.observe(&s).unwrap();
    let Observation::Compass(h) = o["compass"] else {
        panic!()
    };
    assert!((h - std::f32::consts::FRAC_PI_2).abs() < 1e-5, "{h}");
    // Start faces -X; moving 1 m along -X is 1 m forward, i.e. -1 along the start frame's z.
    let Observation::Gps(g) = o["gps"] else {
        panic!()
    };
    assert!(
        (Vec3::from_array(g) - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-5,
        "{g:?}"
    );
    assert_eq!(o["pose"], Observation::Pose(s.base));
    assert_eq!(o["collision"], Observation::Collision(s.collision));
}

#[test]
fn panorama_views_equal_single_renders_at_the_same_yaw() {
    let scene = demo_scene(2);
    let mesh = Arc::new(SceneMesh::new(&scene).unwrap());
    let pano = PanoramaSpec {
        camera: CameraSpec {
            width: 96,
            height: 64,
            ..CameraSpec::default()
        },
        semantic: true,
        ..PanoramaSpec::default()
    };
    let base = common::free_poses(&scene, 1, 3, 1.25, 0.2)[0];
    let mut backends: Vec<Box<dyn Renderer>> = vec![Box::new(RaycastRenderer::new())];
    if let Some(g) = common::gpu("panorama_views_equal_single_renders_at_the_same_yaw") {
        backends.push(Box::new(g));
    }
    for mut single in backends {
        let name = single.name();
        let backend = if name == "wgpu" {
            Backend::Wgpu
        } else {
            Backend::Raycast
        };
        let mut rig = SensorRig::new(RigConfig {
            backend,
            seed: 0,
            sensors: vec![SensorSpec::Panorama(pano.clone())],
        })
        .unwrap();
        rig.set_scene(&scene).unwrap();
        let o = rig
            .observe(&AgentState {
                base,
                ..AgentState::at(Vec3::ZERO, 0.0)
            })
            .unwrap();
        let Observation::Panorama(frames) = &o["panorama"] else {
            panic!()
        };
        assert_eq!(frames.len(), 12);
        single.set_scene(mesh.clone()).unwrap();
        for (k, f) in frames.iter().enumerate() {
            let yaw = base.yaw() + (30.0 * k as f32).to_radians();
            let cam = pano.camera.camera(&Pose::from_yaw(base.translation(), yaw));
            let one = &single
                .render(&[View {
                    camera: cam,
                    channels: Channels {
                        rgb: true,
                        depth: true,
                        semantic: true,
                        instance: false,
                    },
                }])
                .unwrap()[0];
            let same = f
                .semantic
                .iter()
                .zip(&one.semantic)
                .filter(|(a, b)| a == b)
                .count();
            assert!(
                same as f64 >= 0.999 * f.semantic.len() as f64,
                "{name} view {k}: {same}"
            );
            let close = f
                .depth
                .iter()
                .zip(&one.depth)
                .filter(|(a, b)| (*a - *b).abs() < 1e-3)
                .count();
            assert!(
                close as f64 >= 0.999 * f.depth.len() as f64,
                "{name} view {k}: {close}"
            );
        }
    }
}

#[test]
fn lidar_ranges_equal_direct_ray_casts() {
    let scene = demo_scene(4);
    let mesh = Arc::new(SceneMesh::new(&scene).unwrap());
    let rc = SceneRaycaster::new(mesh).unwrap();
    for spec in [
        LidarSpec::default(),
        LidarSpec {
            name: "lidar3d".into(),
            beams: 90,
            channels: 16,
            hfov_deg: 270.0,
            ..LidarSpec::default()
        },
    ] {
        let base = common::free_poses(&scene, 1, 9, spec.mount.offset[1], 0.1)[0];
        let scan = vlnverse_sensors::lidar::scan(&spec, &base, &rc);
        assert_eq!(scan.ranges.len(), (spec.beams * spec.channels) as usize);
        let pose = spec.mount.world_pose(&base);
        for k in 0..spec.channels {
            for i in 0..spec.beams {
                let d = pose.quat() * vlnverse_sensors::lidar::beam_direction(&spec, k, i);
                let want = rc
                    .cast(pose.translation(), d, spec.range_max)
                    .map_or(f32::INFINITY, |h| h.distance);
                assert_eq!(scan.ranges[(k * spec.beams + i) as usize], want);
            }
        }
        assert!(
            scan.ranges.iter().all(|r| r.is_finite()),
            "a closed home returns every beam"
        );
    }
}

#[test]
fn lidar_2d_in_a_box_room_reads_the_wall_distances() {
    // Only the floor and the four outer walls: from (2, 0.3, 3) the beam straight ahead (-Z)
    // reads 3 m, left (-X) 2 m, behind (+Z) 3 m, right (+X) 6 m.
    let mut scene = demo_scene(0);
    scene.objects.retain(|o| {
        o.class == vlnverse_env::SemanticClass::Floor
            || (o.class == vlnverse_env::SemanticClass::Wall
                && o.bbox.size().x.min(o.bbox.size().z) > 0.09
                && (o.bbox.min[0] < 0.0
                    || o.bbox.max[0] > 8.0
                    || o.bbox.min[2] < 0.0
                    || o.bbox.max[2] > 6.0))
    });
    let mut rig = SensorRig::new(RigConfig {
        backend: Backend::Raycast,
        seed: 0,
        sensors: vec![SensorSpec::Lidar(LidarSpec {
            beams: 4,
            ..LidarSpec::default()
        })],
    })
    .unwrap();
    rig.set_scene(&scene).unwrap();
    let o = rig
        .observe(&AgentState::at(Vec3::new(2.0, 0.0, 3.0), 0.0))
        .unwrap();
    let Observation::Lidar(scan) = &o["lidar"] else {
        panic!()
    };
    // Beams at -180, -90, 0, 90 deg: behind, right, ahead, left.
    let want = [3.0, 6.0, 3.0, 2.0];
    for (r, w) in scan.ranges.iter().zip(want) {
        assert!((r - w).abs() < 1e-4, "{:?}", scan.ranges);
    }
}

#[test]
fn noise_is_seeded_and_dropout_marks_nan() {
    let spec = LidarSpec {
        range_stddev: 0.02,
        dropout: 0.2,
        ..LidarSpec::default()
    };
    let rgb = CameraSpec {
        width: 32,
        height: 32,
        noise: Noise::Gaussian { stddev: 8.0 },
        ..CameraSpec::default()
    };
    let depth = CameraSpec {
        width: 32,
        height: 32,
        noise: Noise::KINECT,
        ..CameraSpec::depth()
    };
    let sensors = vec![
        SensorSpec::Lidar(spec),
        SensorSpec::Rgb(rgb),
        SensorSpec::Depth(depth),
    ];
    let s = AgentState::at(Vec3::new(3.5, 0.0, 4.0), 0.3);
    let a = raycast_rig(sensors.clone()).observe(&s).unwrap();
    let b = raycast_rig(sensors.clone()).observe(&s).unwrap();
    let fmt = |o: &vlnverse_sensors::Observations| format!("{o:?}");
    assert_eq!(fmt(&a), fmt(&b), "same seed, same observations");
    let Observation::Lidar(scan) = &a["lidar"] else {
        panic!()
    };
    let nan = scan.ranges.iter().filter(|r| r.is_nan()).count();
    assert!((40..110).contains(&nan), "{nan} of 360 dropped at p = 0.2");
    let mut clean = raycast_rig(vec![SensorSpec::Rgb(CameraSpec {
        width: 32,
        height: 32,
        ..CameraSpec::default()
    })]);
    let c = clean.observe(&s).unwrap();
    assert_ne!(a["rgb"], c["rgb"], "rgb noise changes pixels");
}
