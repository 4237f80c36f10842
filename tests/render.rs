//! Pictures of the LR: sizes, where the mesh is and is not, the colours of ring order and of
//! the triangle classes, the PNG bytes, and meshes with every kind of defect.

mod common;

use lrmesh::generate::{self, Rng};
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::lr::{CompactLr, CompactOptions, Lr, LrInspect, LrOptions, TriangleClass};
use lrmesh::render::{self, ColorMode, Image, RenderOptions, BACKGROUND};
use lrmesh::{CornerOps, CornerTable, Error, Mesh, Vertex};

fn corpus(name: &str) -> Mesh {
    read_mesh(&common::corpus_dir().join(name), &ReadOptions::default())
        .unwrap()
        .mesh
}

/// The LR of `mesh` and its positions by LR vertex.
fn lr_of(mesh: &Mesh) -> (Lr, Vec<[f32; 3]>) {
    let table = CornerTable::from_mesh(mesh).unwrap();
    let lr = Lr::build(&table, &LrOptions::default()).unwrap();
    let positions = (0..lr.vertex_id_bound())
        .map(|v| mesh.positions[lr.input_vertex(Vertex(v)) as usize])
        .collect();
    (lr, positions)
}

fn draw(mesh: &Mesh, options: &RenderOptions) -> Image {
    let (lr, positions) = lr_of(mesh);
    render::render(lr.tables(), &positions, options).unwrap()
}

fn pixels(image: &Image) -> impl Iterator<Item = [u8; 3]> + '_ {
    image.rgb().chunks_exact(3).map(|p| [p[0], p[1], p[2]])
}

fn is_blue(p: [u8; 3]) -> bool {
    let [r, g, b] = p.map(|x| x as u32);
    b > 60 && 2 * r < b && 2 * g < b
}

fn is_red(p: [u8; 3]) -> bool {
    let [r, g, b] = p.map(|x| x as u32);
    r > 60 && 2 * g < r && 2 * b < r
}

fn is_green(p: [u8; 3]) -> bool {
    let [r, g, b] = p.map(|x| x as u32);
    g > 60 && 3 * r < 2 * g && 3 * b < 2 * g
}

#[test]
fn ring_mode_goes_from_blue_to_red_on_a_white_background() {
    let options = RenderOptions {
        width: 320,
        height: 200,
        ..RenderOptions::default()
    };
    let image = draw(&corpus("bunny_small.obj"), &options);
    assert_eq!((image.width(), image.height()), (320, 200));
    assert_eq!(image.rgb().len(), 320 * 200 * 3);
    let blue = pixels(&image).filter(|&p| is_blue(p)).count();
    let red = pixels(&image).filter(|&p| is_red(p)).count();
    let background = pixels(&image).filter(|&p| p == BACKGROUND).count();
    assert!(blue > 200, "{blue} near-blue pixels");
    assert!(red > 200, "{red} near-red pixels");
    // The fitted view leaves a margin and the bunny is not a rectangle.
    assert!(background > 320 * 200 / 5 && background < 320 * 200 * 9 / 10);
    for (x, y) in [(0, 0), (319, 0), (0, 199), (319, 199)] {
        assert_eq!(image.pixel(x, y), Some(BACKGROUND), "corner {x},{y}");
    }
    assert_eq!(image.pixel(320, 0), None);
}

/// Signed distance in pixels from `q` into triangle `p` (positive inside).
fn inside_distance(p: [[f32; 3]; 3], q: [f32; 2]) -> f32 {
    let area =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if area == 0.0 {
        return f32::MIN;
    }
    (0..3)
        .map(|i| {
            let (u, w) = (p[i], p[(i + 1) % 3]);
            let (ex, ey) = (w[0] - u[0], w[1] - u[1]);
            let cross = ex * (q[1] - u[1]) - ey * (q[0] - u[0]);
            area.signum() * cross / (ex * ex + ey * ey).sqrt()
        })
        .fold(f32::MAX, f32::min)
}

/// Without supersampling, a pixel is background exactly when its centre is in no projected
/// triangle (up to a hundredth of a pixel at the edges).
fn check_coverage(mesh: &Mesh, options: &RenderOptions) {
    let (lr, positions) = lr_of(mesh);
    let image = render::render(lr.tables(), &positions, options).unwrap();
    let camera = render::camera(lr.tables(), &positions, options);
    let projected: Vec<[[f32; 3]; 3]> = lr
        .triangles()
        .filter_map(|t| {
            let [a, b, c] = lr
                .triangle_vertices(t)
                .map(|v| camera.project(positions[v.idx()]));
            Some([a?, b?, c?])
        })
        .collect();
    let (mut covered, mut empty) = (0, 0);
    for y in 0..image.height() {
        for x in 0..image.width() {
            let q = [x as f32 + 0.5, y as f32 + 0.5];
            let depth = projected
                .iter()
                .map(|&p| inside_distance(p, q))
                .fold(f32::MIN, f32::max);
            let pixel = image.pixel(x, y).unwrap();
            if depth > 0.01 {
                assert_ne!(pixel, BACKGROUND, "pixel {x},{y} is inside a triangle");
                covered += 1;
            } else if depth < -0.01 {
                assert_eq!(pixel, BACKGROUND, "pixel {x},{y} is outside every triangle");
                empty += 1;
            }
        }
    }
    assert!(covered > 0 && empty > 0, "{covered} covered, {empty} empty");
}

#[test]
fn background_is_where_no_triangle_projects() {
    let options = RenderOptions {
        width: 120,
        height: 90,
        samples: 1,
        ..RenderOptions::default()
    };
    // Boundaries and genus, an open polyhedron, and a perspective view from below.
    check_coverage(&corpus("elephant-with-holes.off"), &options);
    check_coverage(&corpus("hedra_open.off"), &options);
    check_coverage(
        &corpus("knot1.off"),
        &RenderOptions {
            perspective: true,
            azimuth: -70.0,
            elevation: -35.0,
            mode: ColorMode::Classes,
            ..options
        },
    );
}

#[test]
fn classes_mode_shows_every_class_the_lr_has() {
    let mesh = corpus("fandisk.off");
    let (lr, positions) = lr_of(&mesh);
    let count = |class| {
        lr.triangles()
            .filter(|&t| lr.tables().triangle_class(t) == Some(class))
            .count()
    };
    let (t0, t0w, t2) = (
        count(TriangleClass::T0),
        count(TriangleClass::T0Wart),
        count(TriangleClass::T2) + count(TriangleClass::T2Wart),
    );
    assert!(t0 > 0 && t0w > 0 && t2 > 0, "T0 {t0}, T0^w {t0w}, T2 {t2}");
    let t1 = count(TriangleClass::T1Left) + count(TriangleClass::T1Right);
    assert_eq!(t0 + t0w + t2 + t1, lr.triangles().count());
    assert_eq!(lr.counts().t0 as usize, t0);
    assert_eq!(lr.counts().t0_wart as usize, t0w);

    let options = RenderOptions {
        width: 400,
        height: 300,
        mode: ColorMode::Classes,
        ..RenderOptions::default()
    };
    let image = render::render(lr.tables(), &positions, &options).unwrap();
    let green = pixels(&image).filter(|&p| is_green(p)).count();
    let red = pixels(&image).filter(|&p| is_red(p)).count();
    let blue = pixels(&image).filter(|&p| is_blue(p)).count();
    // T1 is neutral: most of the covered pixels are warm light tones.
    let neutral = pixels(&image)
        .filter(|&p| {
            p != BACKGROUND && p[0] >= p[1] && p[1] >= p[2] && p[2] as u32 * 2 > p[0] as u32
        })
        .count();
    let covered = pixels(&image).filter(|&p| p != BACKGROUND).count();
    assert!(green > 20 && red > 20 && blue > 20, "{green} {red} {blue}");
    assert!(2 * neutral > covered, "{neutral} neutral of {covered}");
    // The ring mode has no neutral majority.
    let ring = render::render(
        lr.tables(),
        &positions,
        &RenderOptions {
            mode: ColorMode::Ring,
            ..options
        },
    )
    .unwrap();
    let ring_neutral = pixels(&ring)
        .filter(|&p| {
            p != BACKGROUND && p[0] >= p[1] && p[1] >= p[2] && p[2] as u32 * 2 > p[0] as u32
        })
        .count();
    assert!(ring_neutral < neutral / 4);
}

#[test]
fn ring_lines_darken_pixels() {
    let mesh = corpus("double-torus-3-holes.off");
    let options = RenderOptions {
        width: 200,
        height: 150,
        mode: ColorMode::Classes,
        ..RenderOptions::default()
    };
    let dark = |image: &Image| pixels(image).filter(|p| p.iter().all(|&c| c < 60)).count();
    let plain = draw(&mesh, &options);
    let lines = draw(
        &mesh,
        &RenderOptions {
            ring_lines: true,
            ..options
        },
    );
    assert!(dark(&lines) > dark(&plain) + 100);
}

#[test]
fn png_holds_the_pixels() {
    let image = draw(
        &corpus("icosahedron.off"),
        &RenderOptions {
            width: 64,
            height: 48,
            ..RenderOptions::default()
        },
    );
    let mut bytes = Vec::new();
    image.write_png(&mut bytes).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (64, 48));
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(&buf[..info.buffer_size()], image.rgb());
}

#[test]
fn every_corpus_mesh_and_broken_meshes_render() {
    let options = RenderOptions {
        width: 48,
        height: 40,
        ..RenderOptions::default()
    };
    let mut meshes: Vec<Mesh> = std::fs::read_dir(common::corpus_dir())
        .unwrap()
        .filter_map(|e| read_mesh(&e.unwrap().path(), &ReadOptions::default()).ok())
        .map(|l| l.mesh)
        .collect();
    assert!(meshes.len() > 10);
    let mut rng = Rng::new(7);
    let mut defective = generate::torus(12, 9);
    generate::append(&mut defective, &generate::torus(5, 4));
    generate::add_defects(&mut defective, 40, &mut rng);
    meshes.push(defective);
    meshes.push(generate::soup(30, 60, &mut rng));
    let mut nan = generate::torus(6, 5);
    nan.positions[3] = [f32::NAN, 0.0, f32::INFINITY];
    meshes.push(nan);
    let mut flat = generate::torus(6, 5);
    for p in &mut flat.positions {
        *p = [1.0, 2.0, 3.0];
    }
    meshes.push(flat);
    let drawable = meshes.len() - 2; // the NaN and flat meshes may draw nothing
    meshes.push(Mesh::new(vec![[0.0; 3]; 3], Vec::new()));
    for (k, mesh) in meshes.iter().enumerate() {
        for mode in [ColorMode::Ring, ColorMode::Classes] {
            for (perspective, elevation) in [(false, 90.0), (true, -90.0), (true, 10.0)] {
                let image = draw(
                    mesh,
                    &RenderOptions {
                        mode,
                        perspective,
                        elevation,
                        ring_lines: true,
                        ..options
                    },
                );
                assert_eq!((image.width(), image.height()), (48, 40));
                let drawn = pixels(&image).filter(|&p| p != BACKGROUND).count();
                if k < drawable {
                    assert!(drawn > 0, "mesh {k}: nothing drawn");
                } else if mesh.triangles.is_empty() {
                    assert_eq!(drawn, 0, "mesh {k}: drawn without triangles");
                }
            }
        }
    }
}

#[test]
fn sizes_beyond_the_limit_are_refused() {
    let (lr, positions) = lr_of(&corpus("tetrahedron.off"));
    let options = RenderOptions {
        width: 16384,
        height: 16384,
        samples: 1,
        ..RenderOptions::default()
    };
    assert!(matches!(
        render::render(lr.tables(), &positions, &options),
        Err(Error::LimitExceeded { .. })
    ));
    assert!(matches!(
        render::render(lr.tables(), &positions[..1], &RenderOptions::default()),
        Err(Error::InvalidArgument(_))
    ));
}

#[test]
fn compact_lr_renders_as_the_standard_lr_it_encodes() {
    let mesh = corpus("mech-holes-shark.off");
    let table = CornerTable::from_mesh(&mesh).unwrap();
    let compact = CompactLr::build(&table, &CompactOptions::default()).unwrap();
    let standard =
        Lr::build_with_period(&table, &CompactOptions::default().lr, compact.period()).unwrap();
    let positions: Vec<[f32; 3]> = (0..standard.vertex_id_bound())
        .map(|v| mesh.positions[standard.input_vertex(Vertex(v)) as usize])
        .collect();
    let count = |lr: &dyn Fn(lrmesh::Triangle) -> Option<TriangleClass>, class| {
        (0..standard
            .triangle_id_bound()
            .max(compact.tables().triangle_id_bound()))
            .filter(|&t| lr(lrmesh::Triangle(t)) == Some(class))
            .count()
    };
    let classes = [
        TriangleClass::T0,
        TriangleClass::T0Wart,
        TriangleClass::T1Left,
        TriangleClass::T1Right,
        TriangleClass::T2,
        TriangleClass::T2Wart,
    ];
    for class in classes {
        assert_eq!(
            count(&|t| compact.tables().triangle_class(t), class),
            count(&|t| standard.tables().triangle_class(t), class),
            "{class:?}"
        );
    }
    assert_eq!(
        count(&|t| compact.tables().triangle_class(t), TriangleClass::T0),
        compact.counts().t0 as usize
    );
    for mode in [ColorMode::Ring, ColorMode::Classes] {
        let options = RenderOptions {
            width: 160,
            height: 120,
            mode,
            ..RenderOptions::default()
        };
        assert_eq!(
            render::render(compact.tables(), &positions, &options).unwrap(),
            render::render(standard.tables(), &positions, &options).unwrap(),
            "{mode:?}"
        );
    }
}
