// campo replay viewer.
//
// Plain script (no modules, no network): it reads the run data embedded in
// <script id="campo-data" type="application/json"> and draws it with the global THREE
// (three.js r147 build/three.min.js) and THREE.OrbitControls. World frame: x east, y north, z up.
//
// Test hooks (URL hash, e.g. "#t=5&camera=ex,ey,ez,tx,ty,tz&fov=50&view=silhouette"):
//   t=SECONDS      moves the time slider there and dispatches an "input" event (the user's code path)
//   camera=...     camera position and orbit target in the world frame
//   fov=DEG        vertical field of view (default 50)
//   view=silhouette  black background, static solids pure white and unlit, everything else hidden
// After the first frame and after every time change the state is written to document.body.dataset:
//   data-ready, data-time, data-vehicles ("x,y,z;x,y,z"), data-scan-points.
(function () {
  'use strict';

  var DEFAULT_FOV_DEG = 50;
  var TUBE_SIDES = 8;
  var PALETTE = [[0.12, 0.47, 0.71], [0.84, 0.15, 0.16], [0.17, 0.63, 0.17], [1.0, 0.5, 0.05],
                 [0.58, 0.4, 0.74], [0.55, 0.34, 0.29]];

  // ---------------------------------------------------------------- small helpers

  function showMessage(text) {
    var box = document.getElementById('message');
    if (box) {
      box.textContent = text;
      box.style.display = 'block';
    }
  }

  function isNum(v) {
    return typeof v === 'number' && isFinite(v);
  }

  function num(v, fallback) {
    return isNum(v) ? v : fallback;
  }

  function vec3(a, fallback) {
    if (Array.isArray(a) && a.length >= 3 && isNum(a[0]) && isNum(a[1]) && isNum(a[2])) {
      return new THREE.Vector3(a[0], a[1], a[2]);
    }
    return fallback ? fallback.clone() : new THREE.Vector3();
  }

  function colorOf(a, fallback) {
    var c = Array.isArray(a) && a.length >= 3 && isNum(a[0]) && isNum(a[1]) && isNum(a[2]) ? a : fallback;
    return new THREE.Color(clamp01(c[0]), clamp01(c[1]), clamp01(c[2]));
  }

  function clamp01(v) {
    return Math.min(1, Math.max(0, v));
  }

  function cssColor(c) {
    return 'rgb(' + Math.round(c.r * 255) + ',' + Math.round(c.g * 255) + ',' + Math.round(c.b * 255) + ')';
  }

  // Local->world rotation from 9 row-major numbers; identity when absent or malformed.
  function rotationQuaternion(r) {
    var q = new THREE.Quaternion();
    if (Array.isArray(r) && r.length === 9 && r.every(isNum)) {
      var m = new THREE.Matrix4();
      m.set(r[0], r[1], r[2], 0, r[3], r[4], r[5], 0, r[6], r[7], r[8], 0, 0, 0, 0, 1);
      q.setFromRotationMatrix(m);
    }
    return q;
  }

  // Index i and fraction f with times[i] <= t < times[i+1] (clamped at both ends).
  function locate(times, t) {
    var n = times.length;
    if (n === 0) return { i: 0, f: 0 };
    if (!(t > times[0])) return { i: 0, f: 0 };
    if (t >= times[n - 1]) return { i: n - 1, f: 0 };
    var lo = 0;
    var hi = n - 1;
    while (hi - lo > 1) {
      var mid = (lo + hi) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid;
    }
    var span = times[lo + 1] - times[lo];
    return { i: lo, f: span > 0 ? (t - times[lo]) / span : 0 };
  }

  function lerp(a, b, f) {
    return f === 0 ? a : a + (b - a) * f;
  }

  // Angle interpolation along the shorter way round (degrees).
  function lerpAngleDeg(a, b, f) {
    if (f === 0) return a;
    var d = ((b - a) % 360 + 540) % 360 - 180;
    return a + d * f;
  }

  // Time series of [x,y,z] samples, cleaned: only finite samples in non-decreasing time order are kept.
  function cleanSeries(times, values) {
    var out = { times: [], values: [] };
    if (!Array.isArray(times) || !Array.isArray(values)) return out;
    var n = Math.min(times.length, values.length);
    for (var k = 0; k < n; k++) {
      var t = times[k];
      var v = values[k];
      if (!isNum(t) || !Array.isArray(v) || v.length < 3 || !isNum(v[0]) || !isNum(v[1]) || !isNum(v[2])) continue;
      if (out.times.length > 0 && t < out.times[out.times.length - 1]) continue;
      out.times.push(t);
      out.values.push([v[0], v[1], v[2]]);
    }
    return out;
  }

  function parseHash() {
    var result = {};
    var text = (window.location.hash || '').replace(/^#/, '');
    text.split('&').forEach(function (part) {
      if (!part) return;
      var eq = part.indexOf('=');
      var key = eq < 0 ? part : part.slice(0, eq);
      var value = eq < 0 ? '' : part.slice(eq + 1);
      try {
        result[decodeURIComponent(key)] = decodeURIComponent(value);
      } catch (e) {
        result[key] = value;
      }
    });
    return result;
  }

  function parseNumberList(text, count) {
    if (typeof text !== 'string') return null;
    var parts = text.split(',');
    if (parts.length !== count) return null;
    var out = [];
    for (var k = 0; k < count; k++) {
      if (parts[k].trim() === '') return null;
      var v = Number(parts[k]);
      if (!isFinite(v)) return null;
      out.push(v);
    }
    return out;
  }

  function niceStep(x) {
    var p = Math.pow(10, Math.floor(Math.log10(x)));
    var m = x / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
  }

  // Round dot / ring sprite for THREE.Points (drawn once into a canvas, no image files).
  function dotTexture(ring) {
    var size = 64;
    var canvas = document.createElement('canvas');
    canvas.width = size;
    canvas.height = size;
    var g = canvas.getContext('2d');
    g.beginPath();
    if (ring) {
      g.arc(size / 2, size / 2, size / 2 - 6, 0, 2 * Math.PI);
      g.lineWidth = 7;
      g.strokeStyle = '#ffffff';
      g.stroke();
    } else {
      g.arc(size / 2, size / 2, size / 2 - 2, 0, 2 * Math.PI);
      g.fillStyle = '#ffffff';
      g.fill();
    }
    var texture = new THREE.CanvasTexture(canvas);
    texture.needsUpdate = true;
    return texture;
  }

  // ---------------------------------------------------------------- start-up checks

  if (typeof THREE === 'undefined' || typeof THREE.OrbitControls === 'undefined') {
    showMessage('three.js is missing: this page was not assembled (campo render --kind replay).');
    return;
  }
  var data;
  try {
    var dataElement = document.getElementById('campo-data');
    data = JSON.parse(dataElement ? dataElement.textContent : '');
  } catch (e) {
    showMessage('No replay data in this page: it was not assembled (campo render --kind replay).');
    return;
  }
  if (!data || typeof data !== 'object' || data.campo_replay !== 1) {
    showMessage('Unsupported replay data (expected "campo_replay": 1).');
    return;
  }

  var hash = parseHash();
  var silhouette = hash.view === 'silhouette';
  var sceneData = data.scene && typeof data.scene === 'object' ? data.scene : {};
  var runsData = Array.isArray(data.runs) ? data.runs : [];

  // ---------------------------------------------------------------- renderer, camera, lights

  var viewport = document.getElementById('viewport');
  // Without antialiasing the silhouette view is strictly two-valued.
  var renderer = new THREE.WebGLRenderer({ antialias: !silhouette, alpha: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.setClearColor(0x000000, 0);
  viewport.appendChild(renderer.domElement);

  var scene = new THREE.Scene();
  var camera = new THREE.PerspectiveCamera(DEFAULT_FOV_DEG, window.innerWidth / Math.max(1, window.innerHeight),
                                           0.1, 1000);
  camera.up.set(0, 0, 1);

  var hemi = new THREE.HemisphereLight(0xeaf2fb, 0x8c8270, 0.7);
  hemi.position.set(0, 0, 1);
  scene.add(hemi);
  var sun = new THREE.DirectionalLight(0xffffff, 0.6);
  scene.add(sun);
  scene.add(sun.target);

  // Groups: what silhouette mode keeps (static solids) and what it hides.
  var staticGroup = new THREE.Group();
  var decorGroup = new THREE.Group();   // plane grids
  var moverGroup = new THREE.Group();
  var runGroup = new THREE.Group();
  scene.add(staticGroup, decorGroup, moverGroup, runGroup);

  var whiteMaterial = new THREE.MeshBasicMaterial({ color: 0xffffff, side: THREE.DoubleSide });
  var staticMeshes = [];   // {mesh, material}: normal material kept for switching views

  // ---------------------------------------------------------------- bounds

  var boundsMin = null;
  var boundsMax = null;
  if (sceneData.bounds_m && typeof sceneData.bounds_m === 'object') {
    var bmin = sceneData.bounds_m.min;
    var bmax = sceneData.bounds_m.max;
    if (Array.isArray(bmin) && Array.isArray(bmax) && bmin.length >= 3 && bmax.length >= 3 &&
        [0, 1, 2].every(function (k) { return isNum(bmin[k]) && isNum(bmax[k]) && bmin[k] <= bmax[k]; })) {
      boundsMin = vec3(bmin);
      boundsMax = vec3(bmax);
    }
  }
  if (!boundsMin) {
    // Fall back to the tracks (and the origin) when the bounds are missing.
    var box = new THREE.Box3(new THREE.Vector3(-1, -1, 0), new THREE.Vector3(1, 1, 1));
    runsData.forEach(function (run) {
      if (run && Array.isArray(run.positions_m)) {
        run.positions_m.forEach(function (p) {
          if (Array.isArray(p) && isNum(p[0]) && isNum(p[1]) && isNum(p[2])) box.expandByPoint(vec3(p));
        });
      }
    });
    boundsMin = box.min;
    boundsMax = box.max;
  }
  var centre = boundsMin.clone().add(boundsMax).multiplyScalar(0.5);
  var extent = boundsMax.clone().sub(boundsMin);
  var sceneRadius = Math.max(0.5 * extent.length(), 0.5);
  var planeSide = 4 * Math.max(extent.x, extent.y, extent.z, 1);
  var reachRadius = sceneRadius;   // radius around centre that holds everything drawn (for clip planes)

  sun.position.copy(centre).add(new THREE.Vector3(-0.45, -0.7, 1.0).multiplyScalar(sceneRadius * 2));
  sun.target.position.copy(centre);

  // ---------------------------------------------------------------- static scene

  function addStatic(mesh) {
    staticGroup.add(mesh);
    staticMeshes.push({ mesh: mesh, material: mesh.material });
  }

  function shapeGeometry(shape) {
    var g = null;
    var radius = num(shape.radius_m, 0);
    var height = num(shape.height_m, 0);
    switch (shape.type) {
      case 'cuboid': {
        var s = Array.isArray(shape.size_m) ? shape.size_m : [];
        if (!(num(s[0], 0) > 0 && num(s[1], 0) > 0 && num(s[2], 0) > 0)) return null;
        g = new THREE.BoxGeometry(s[0], s[1], s[2]);
        break;
      }
      case 'cylinder':
        if (!(radius > 0 && height > 0)) return null;
        g = new THREE.CylinderGeometry(radius, radius, height, 64, 1);
        g.rotateX(Math.PI / 2);   // three's axis is +y; campo's is local +z
        break;
      case 'cone':
        if (!(radius > 0 && height > 0)) return null;
        g = new THREE.ConeGeometry(radius, height, 64, 1);
        g.rotateX(Math.PI / 2);   // apex from +y to +z, base at -h/2
        break;
      case 'sphere':
        if (!(radius > 0)) return null;
        g = new THREE.SphereGeometry(radius, 64, 32);
        break;
      case 'mesh':
        return meshGeometry(Number.isInteger(shape.mesh) ? meshesData[shape.mesh] : null);
      default:
        return null;
    }
    return g;
  }

  // A mesh shape's triangles (scene.meshes, shared by the shapes that use
  // them), flat-shaded and drawn from both sides: files may be open or wound
  // either way. Built once per mesh.
  var meshesData = Array.isArray(sceneData.meshes) ? sceneData.meshes : [];
  var meshGeometries = [];
  function meshGeometry(data) {
    if (!data || typeof data !== 'object') return null;
    var index = meshesData.indexOf(data);
    if (meshGeometries[index]) return meshGeometries[index];
    var v = Array.isArray(data.vertices_m) ? data.vertices_m : [];
    var t = Array.isArray(data.triangles) ? data.triangles : [];
    var count = Math.floor(v.length / 3);
    var positions = new Float32Array(9 * Math.floor(t.length / 3));
    var k = 0;
    for (var i = 0; i + 2 < t.length; i += 3) {
      var ok = true;
      for (var j = 0; j < 3; ++j) {
        var a = t[i + j];
        if (!(Number.isInteger(a) && a >= 0 && a < count)) ok = false;
      }
      if (!ok) continue;
      for (var c = 0; c < 3; ++c) {
        var p = 3 * t[i + c];
        positions[k++] = num(v[p], 0);
        positions[k++] = num(v[p + 1], 0);
        positions[k++] = num(v[p + 2], 0);
      }
    }
    if (k === 0) return null;
    var g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(positions.subarray(0, k), 3));
    g.computeVertexNormals();   // unshared vertices: one normal per face
    meshGeometries[index] = g;
    return g;
  }

  var shapesData = Array.isArray(sceneData.shapes) ? sceneData.shapes : [];
  var moversData = Array.isArray(sceneData.movers) ? sceneData.movers : [];
  var moverShapeIndex = {};
  moversData.forEach(function (mover) {
    if (mover && Number.isInteger(mover.shape)) moverShapeIndex[mover.shape] = true;
  });
  var shapeMeshes = [];
  shapesData.forEach(function (shape, index) {
    shapeMeshes.push(null);
    if (!shape || typeof shape !== 'object') return;
    var geometry = shapeGeometry(shape);
    if (!geometry) return;
    var material = new THREE.MeshLambertMaterial({ color: colorOf(shape.color, [0.6, 0.6, 0.6]) });
    if (shape.type === 'mesh') material.side = THREE.DoubleSide;
    var mesh = new THREE.Mesh(geometry, material);
    mesh.position.copy(vec3(shape.position_m));
    mesh.quaternion.copy(rotationQuaternion(shape.rotation));
    mesh.name = typeof shape.alias === 'string' ? shape.alias : '';
    shapeMeshes[index] = mesh;
    if ((Number.isInteger(shape.mover) && shape.mover >= 0) || moverShapeIndex[index]) {
      moverGroup.add(mesh);
    } else {
      addStatic(mesh);
    }
  });

  (Array.isArray(sceneData.planes) ? sceneData.planes : []).forEach(function (plane) {
    if (!plane || typeof plane !== 'object') return;
    var normal = vec3(plane.normal, new THREE.Vector3(0, 0, 1));
    if (normal.lengthSq() === 0) return;
    normal.normalize();
    var point = vec3(plane.position_m);
    // Centre the finite square on the projection of the scene centre onto the plane.
    var middle = centre.clone().sub(normal.clone().multiplyScalar(centre.clone().sub(point).dot(normal)));
    var orientation = new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 0, 1), normal);
    var color = colorOf(plane.color, [0.78, 0.8, 0.78]);
    var material = new THREE.MeshLambertMaterial({
      color: color, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1
    });
    var mesh = new THREE.Mesh(new THREE.PlaneGeometry(planeSide, planeSide), material);
    mesh.position.copy(middle);
    mesh.quaternion.copy(orientation);
    addStatic(mesh);

    var step = niceStep(planeSide / 40);
    var half = Math.floor(planeSide / 2 / step) * step;
    var lines = [];
    for (var v = -half; v <= half + 1e-9; v += step) {
      lines.push(v, -half, 0, v, half, 0, -half, v, 0, half, v, 0);
    }
    var gridGeometry = new THREE.BufferGeometry();
    gridGeometry.setAttribute('position', new THREE.Float32BufferAttribute(lines, 3));
    var gridColor = color.clone().multiplyScalar(0.6);
    var grid = new THREE.LineSegments(gridGeometry,
                                      new THREE.LineBasicMaterial({ color: gridColor, transparent: true, opacity: 0.25 }));
    grid.position.copy(middle);
    grid.quaternion.copy(orientation);
    decorGroup.add(grid);
    reachRadius = Math.max(reachRadius, middle.distanceTo(centre) + planeSide * Math.SQRT1_2);
  });

  (Array.isArray(sceneData.terrains) ? sceneData.terrains : []).forEach(function (terrain) {
    if (!terrain || typeof terrain !== 'object') return;
    var cols = terrain.cols;
    var rows = terrain.rows;
    var heights = terrain.heights_m;
    var spacing = Array.isArray(terrain.spacing_m) ? terrain.spacing_m : [];
    if (!Number.isInteger(cols) || !Number.isInteger(rows) || cols < 2 || rows < 2) return;
    if (!Array.isArray(heights) || heights.length !== cols * rows) return;
    var dx = num(spacing[0], 0);
    var dy = num(spacing[1], 0);
    if (!(dx > 0 && dy > 0)) return;

    var count = cols * rows;
    var positions = new Float32Array(count * 3);
    var colors = new Float32Array(count * 3);
    var hmin = Infinity;
    var hmax = -Infinity;
    heights.forEach(function (h) {
      if (isNum(h)) {
        hmin = Math.min(hmin, h);
        hmax = Math.max(hmax, h);
      }
    });
    var span = hmax > hmin ? hmax - hmin : 1;
    var tint = colorOf(terrain.color, [0.55, 0.6, 0.45]);
    for (var r = 0; r < rows; r++) {
      for (var c = 0; c < cols; c++) {
        var k = r * cols + c;
        var h = isNum(heights[k]) ? heights[k] : NaN;
        positions[3 * k] = (c - (cols - 1) / 2) * dx;
        positions[3 * k + 1] = (r - (rows - 1) / 2) * dy;
        positions[3 * k + 2] = isNum(h) ? h : 0;
        // Low ground darker, high ground lighter: a tint of the terrain colour.
        var shade = isNum(h) ? 0.62 + 0.55 * (h - hmin) / span : 0.6;
        colors[3 * k] = clamp01(tint.r * shade);
        colors[3 * k + 1] = clamp01(tint.g * shade);
        colors[3 * k + 2] = clamp01(tint.b * shade);
      }
    }
    // Triangulation fixed by the data format: (c,r),(c+1,r),(c,r+1) and (c+1,r),(c+1,r+1),(c,r+1).
    var indices = [];
    function ok(idx) { return isNum(heights[idx]); }
    for (var rr = 0; rr + 1 < rows; rr++) {
      for (var cc = 0; cc + 1 < cols; cc++) {
        var a = rr * cols + cc;
        var b = a + 1;
        var d = a + cols;
        var e = d + 1;
        if (ok(a) && ok(b) && ok(d)) indices.push(a, b, d);
        if (ok(b) && ok(e) && ok(d)) indices.push(b, e, d);
      }
    }
    if (indices.length === 0) return;
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
    geometry.setIndex(new THREE.BufferAttribute(count > 65535 ? new Uint32Array(indices) : new Uint16Array(indices), 1));
    geometry.computeVertexNormals();
    var mesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide }));
    mesh.position.copy(vec3(terrain.position_m));
    mesh.quaternion.copy(rotationQuaternion(terrain.rotation));
    addStatic(mesh);
  });

  // ---------------------------------------------------------------- movers

  var movers = [];
  moversData.forEach(function (mover) {
    if (!mover || !Number.isInteger(mover.shape)) return;
    var mesh = shapeMeshes[mover.shape];
    if (!mesh) return;
    var series = cleanSeries(mover.times_s, mover.positions_m);
    if (series.times.length === 0) return;
    movers.push({ mesh: mesh, series: series });
  });

  // ---------------------------------------------------------------- runs

  // Tube along a polyline: TUBE_SIDES vertices per sample, indices ordered segment by segment so
  // that setDrawRange(0, i * TUBE_SIDES * 6) shows exactly the first i segments.
  function tubeGeometry(points, radius) {
    var n = points.length;
    var positions = new Float32Array(n * TUBE_SIDES * 3);
    var normals = new Float32Array(n * TUBE_SIDES * 3);
    var tangent = new THREE.Vector3(1, 0, 0);
    var normal = null;
    var binormal = new THREE.Vector3();
    var d = new THREE.Vector3();
    var radial = new THREE.Vector3();
    for (var i = 0; i < n; i++) {
      d.subVectors(points[Math.min(i + 1, n - 1)], points[Math.max(i - 1, 0)]);
      if (d.lengthSq() > 1e-18) tangent.copy(d).normalize();
      if (normal) {
        normal.addScaledVector(tangent, -normal.dot(tangent));   // parallel transport
      }
      if (!normal || normal.lengthSq() < 1e-12) {
        var axis = Math.abs(tangent.z) < 0.9 ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(1, 0, 0);
        normal = new THREE.Vector3().crossVectors(axis, tangent);
      }
      normal.normalize();
      binormal.crossVectors(tangent, normal);
      for (var k = 0; k < TUBE_SIDES; k++) {
        var angle = 2 * Math.PI * k / TUBE_SIDES;
        radial.copy(normal).multiplyScalar(Math.cos(angle)).addScaledVector(binormal, Math.sin(angle));
        var o = (i * TUBE_SIDES + k) * 3;
        positions[o] = points[i].x + radius * radial.x;
        positions[o + 1] = points[i].y + radius * radial.y;
        positions[o + 2] = points[i].z + radius * radial.z;
        normals[o] = radial.x;
        normals[o + 1] = radial.y;
        normals[o + 2] = radial.z;
      }
    }
    var segments = Math.max(0, n - 1);
    var indexCount = segments * TUBE_SIDES * 6;
    var index = n * TUBE_SIDES > 65535 ? new Uint32Array(indexCount) : new Uint16Array(indexCount);
    var w = 0;
    for (var s = 0; s < segments; s++) {
      for (var j = 0; j < TUBE_SIDES; j++) {
        var a = s * TUBE_SIDES + j;
        var b = s * TUBE_SIDES + (j + 1) % TUBE_SIDES;
        var c = a + TUBE_SIDES;
        var e = b + TUBE_SIDES;
        index[w++] = a; index[w++] = b; index[w++] = e;
        index[w++] = a; index[w++] = e; index[w++] = c;
      }
    }
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    geometry.setAttribute('normal', new THREE.BufferAttribute(normals, 3));
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    geometry.setDrawRange(0, 0);
    return geometry;
  }

  function quadrotorModel(size, material, discMaterial) {
    var length = size[0];
    var width = size[1];
    var height = size[2];
    var rotorRadius = 0.22 * Math.min(length, width);
    var ax = Math.max(length / 2 - rotorRadius, 0.25 * length);
    var ay = Math.max(width / 2 - rotorRadius, 0.25 * width);
    var armThickness = Math.max(0.18 * height, 0.04 * Math.min(length, width));
    var group = new THREE.Group();
    var body = new THREE.Mesh(new THREE.BoxGeometry(0.3 * length, 0.3 * width, 0.5 * height), material);
    group.add(body);
    var armLength = 2 * Math.sqrt(ax * ax + ay * ay);
    [1, -1].forEach(function (sign) {
      var arm = new THREE.Mesh(new THREE.BoxGeometry(armLength, armThickness, armThickness), material);
      arm.rotation.z = sign * Math.atan2(ay, ax);
      group.add(arm);
    });
    var discGeometry = new THREE.CylinderGeometry(rotorRadius, rotorRadius, Math.max(0.04 * height, 0.005), 32);
    discGeometry.rotateX(Math.PI / 2);
    [[1, 1], [1, -1], [-1, 1], [-1, -1]].forEach(function (s) {
      var disc = new THREE.Mesh(discGeometry, discMaterial);
      disc.position.set(s[0] * ax, s[1] * ay, 0.5 * armThickness + 0.02 * height);
      group.add(disc);
    });
    // Nose marker so the heading (+x body axis) is visible.
    var nose = new THREE.Mesh(new THREE.SphereGeometry(0.09 * Math.min(length, width), 16, 8),
                              new THREE.MeshLambertMaterial({ color: 0xffffff }));
    nose.position.set(0.15 * length + 0.05 * Math.min(length, width), 0, 0);
    group.add(nose);
    return group;
  }

  function roverModel(size, material) {
    var group = new THREE.Group();
    var box = new THREE.BoxGeometry(size[0], size[1], size[2]);
    group.add(new THREE.Mesh(box, material));
    var edges = new THREE.LineSegments(new THREE.EdgesGeometry(box),
                                       new THREE.LineBasicMaterial({ color: 0x1d2733, transparent: true, opacity: 0.5 }));
    group.add(edges);
    // Front stripe so the heading (+x body axis) is visible.
    var stripe = new THREE.Mesh(new THREE.BoxGeometry(0.02 * size[0] + 0.005, 0.8 * size[1], 0.35 * size[2]),
                                new THREE.MeshLambertMaterial({ color: 0xffffff }));
    stripe.position.set(size[0] / 2, 0, 0.1 * size[2]);
    group.add(stripe);
    return group;
  }

  var dotMap = dotTexture(false);
  var ringMap = dotTexture(true);
  var runs = [];
  runsData.forEach(function (run, runIndex) {
    if (!run || typeof run !== 'object') return;
    var color = colorOf(run.color, PALETTE[runIndex % PALETTE.length]);
    var label = typeof run.label === 'string' && run.label ? run.label : 'run ' + (runIndex + 1);
    var group = new THREE.Group();
    runGroup.add(group);

    // Pose samples: positions and (when complete) roll/pitch/yaw.
    var times = [];
    var points = [];
    var rpy = [];
    var rpyOk = Array.isArray(run.rpy_deg);
    var n = Array.isArray(run.times_s) && Array.isArray(run.positions_m) ?
      Math.min(run.times_s.length, run.positions_m.length) : 0;
    for (var k = 0; k < n; k++) {
      var t = run.times_s[k];
      var p = run.positions_m[k];
      if (!isNum(t) || !Array.isArray(p) || !isNum(p[0]) || !isNum(p[1]) || !isNum(p[2])) continue;
      if (times.length > 0 && t < times[times.length - 1]) continue;
      var a = rpyOk ? run.rpy_deg[k] : null;
      times.push(t);
      points.push(new THREE.Vector3(p[0], p[1], p[2]));
      rpy.push(Array.isArray(a) && isNum(a[0]) && isNum(a[1]) && isNum(a[2]) ? [a[0], a[1], a[2]] : [0, 0, 0]);
    }

    var size = Array.isArray(run.size_m) && run.size_m.length >= 3 &&
      run.size_m.slice(0, 3).every(function (v) { return isNum(v) && v > 0; }) ? run.size_m.slice(0, 3) : [0.5, 0.5, 0.2];
    var tubeRadius = Math.min(Math.max(0.0025 * sceneRadius, 0.01), 0.1 * Math.max(size[0], size[1]));

    var entry = {
      label: label, color: color, group: group, times: times, points: points, rpy: rpy,
      outcome: typeof run.outcome === 'string' ? run.outcome : '',
      vehicleType: run.vehicle === 'rover' ? 'rover' : 'quadrotor',
      position: points.length ? points[0].clone() : new THREE.Vector3(),
      segment: -1, scanIndex: -2, scanCount: 0
    };

    if (points.length >= 2) {
      var full = new THREE.BufferGeometry().setFromPoints(points);
      group.add(new THREE.Line(full, new THREE.LineBasicMaterial({ color: color, transparent: true, opacity: 0.35 })));
    }
    var bright = new THREE.MeshLambertMaterial({ color: color, emissive: color.clone().multiplyScalar(0.35) });
    entry.travelled = new THREE.Mesh(tubeGeometry(points.length ? points : [new THREE.Vector3()], tubeRadius), bright);
    entry.travelled.frustumCulled = false;
    group.add(entry.travelled);
    // Last partial segment, from the latest sample to the vehicle.
    var tipGeometry = new THREE.CylinderGeometry(tubeRadius, tubeRadius, 1, TUBE_SIDES, 1, true);
    tipGeometry.translate(0, 0.5, 0);
    entry.tip = new THREE.Mesh(tipGeometry, bright);
    entry.tip.visible = false;
    group.add(entry.tip);

    var bodyMaterial = new THREE.MeshLambertMaterial({ color: color, emissive: color.clone().multiplyScalar(0.15) });
    if (entry.vehicleType === 'rover') {
      entry.vehicle = roverModel(size, bodyMaterial);
    } else {
      var discMaterial = new THREE.MeshLambertMaterial({
        color: color.clone().lerp(new THREE.Color(1, 1, 1), 0.45), transparent: true, opacity: 0.75
      });
      entry.vehicle = quadrotorModel(size, bodyMaterial, discMaterial);
    }
    entry.vehicle.visible = points.length > 0;
    group.add(entry.vehicle);

    // Screen-space ring so small vehicles stay findable in wide shots.
    var markerGeometry = new THREE.BufferGeometry();
    markerGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3), 3));
    entry.marker = new THREE.Points(markerGeometry, new THREE.PointsMaterial({
      color: color, size: 22, sizeAttenuation: false, map: ringMap, transparent: true, depthTest: false, opacity: 0.9
    }));
    entry.marker.renderOrder = 10;
    entry.marker.frustumCulled = false;
    entry.marker.visible = points.length > 0;
    group.add(entry.marker);

    // Scans: one buffer sized for the largest scan, refilled when the shown scan changes.
    var scans = [];
    var maxPoints = 0;
    (Array.isArray(run.scans) ? run.scans : []).forEach(function (scan) {
      if (!scan || !isNum(scan.time_s) || !Array.isArray(scan.points_m)) return;
      if (scans.length > 0 && scan.time_s < scans[scans.length - 1].time) return;
      var flat = [];
      scan.points_m.forEach(function (q) {
        if (Array.isArray(q) && isNum(q[0]) && isNum(q[1]) && isNum(q[2])) flat.push(q[0], q[1], q[2]);
      });
      scans.push({ time: scan.time_s, points: new Float32Array(flat) });
      maxPoints = Math.max(maxPoints, flat.length / 3);
    });
    entry.scans = scans;
    entry.scanTimes = scans.map(function (s) { return s.time; });
    if (maxPoints > 0) {
      var scanGeometry = new THREE.BufferGeometry();
      var scanAttribute = new THREE.BufferAttribute(new Float32Array(maxPoints * 3), 3);
      scanAttribute.setUsage(THREE.DynamicDrawUsage);
      scanGeometry.setAttribute('position', scanAttribute);
      scanGeometry.setDrawRange(0, 0);
      var scanColor = color.clone().lerp(new THREE.Color(0, 0, 0), 0.25);
      entry.scanPoints = new THREE.Points(scanGeometry, new THREE.PointsMaterial({
        color: scanColor, size: 5, sizeAttenuation: false, map: dotMap, alphaTest: 0.5
      }));
      entry.scanPoints.frustumCulled = false;
      group.add(entry.scanPoints);
    }
    runs.push(entry);
  });

  // ---------------------------------------------------------------- time

  var duration = num(data.duration_s, 0);
  if (!(duration > 0)) {
    runs.forEach(function (run) {
      if (run.times.length) duration = Math.max(duration, run.times[run.times.length - 1]);
    });
    movers.forEach(function (m) { duration = Math.max(duration, m.series.times[m.series.times.length - 1]); });
  }
  if (!(duration > 0)) duration = 0;
  var currentTime = 0;

  var euler = new THREE.Euler(0, 0, 0, 'ZYX');   // R = Rz(yaw) Ry(pitch) Rx(roll)
  var direction = new THREE.Vector3();
  var yAxis = new THREE.Vector3(0, 1, 0);

  function updateRun(run, t) {
    if (run.points.length === 0) return;
    var loc = locate(run.times, t);
    var i = loc.i;
    var f = loc.f;
    var p0 = run.points[i];
    if (f > 0) {
      var p1 = run.points[i + 1];
      run.position.set(lerp(p0.x, p1.x, f), lerp(p0.y, p1.y, f), lerp(p0.z, p1.z, f));
    } else {
      run.position.copy(p0);
    }
    var a0 = run.rpy[i];
    var a1 = f > 0 ? run.rpy[i + 1] : a0;
    euler.set(THREE.MathUtils.degToRad(lerpAngleDeg(a0[0], a1[0], f)),
              THREE.MathUtils.degToRad(lerpAngleDeg(a0[1], a1[1], f)),
              THREE.MathUtils.degToRad(lerpAngleDeg(a0[2], a1[2], f)), 'ZYX');
    run.vehicle.position.copy(run.position);
    run.vehicle.quaternion.setFromEuler(euler);
    run.marker.geometry.attributes.position.setXYZ(0, run.position.x, run.position.y, run.position.z);
    run.marker.geometry.attributes.position.needsUpdate = true;

    if (i !== run.segment) {
      run.travelled.geometry.setDrawRange(0, i * TUBE_SIDES * 6);
      run.segment = i;
    }
    direction.subVectors(run.position, p0);
    var length = direction.length();
    if (length > 1e-9) {
      run.tip.position.copy(p0);
      run.tip.quaternion.setFromUnitVectors(yAxis, direction.divideScalar(length));
      run.tip.scale.set(1, length, 1);
      run.tip.visible = true;
    } else {
      run.tip.visible = false;
    }

    if (run.scanPoints) {
      // Latest scan at or before t (none before the first scan).
      var s = -1;
      var lo = 0;
      var hi = run.scanTimes.length - 1;
      while (lo <= hi) {
        var mid = (lo + hi) >> 1;
        if (run.scanTimes[mid] <= t) { s = mid; lo = mid + 1; } else { hi = mid - 1; }
      }
      if (s !== run.scanIndex) {
        var attribute = run.scanPoints.geometry.attributes.position;
        var count = 0;
        if (s >= 0) {
          attribute.array.set(run.scans[s].points);
          count = run.scans[s].points.length / 3;
          attribute.needsUpdate = true;
        }
        run.scanPoints.geometry.setDrawRange(0, count);
        run.scanIndex = s;
        run.scanCount = count;
      }
    }
  }

  function updateMovers(t) {
    movers.forEach(function (m) {
      var loc = locate(m.series.times, t);
      var p0 = m.series.values[loc.i];
      if (loc.f > 0) {
        var p1 = m.series.values[loc.i + 1];
        m.mesh.position.set(lerp(p0[0], p1[0], loc.f), lerp(p0[1], p1[1], loc.f), lerp(p0[2], p1[2], loc.f));
      } else {
        m.mesh.position.set(p0[0], p0[1], p0[2]);
      }
    });
  }

  // ---------------------------------------------------------------- UI

  var slider = document.getElementById('time');
  var playButton = document.getElementById('play');
  var speedSelect = document.getElementById('speed');
  var clock = document.getElementById('clock');
  var legend = document.getElementById('legend');

  var title = typeof data.title === 'string' && data.title ? data.title : 'campo replay';
  document.title = title === 'campo replay' ? title : title + ' - campo replay';
  document.getElementById('heading').textContent = title;
  var subtitleParts = [];
  if (typeof sceneData.name === 'string' && sceneData.name) subtitleParts.push('scene ' + sceneData.name);
  subtitleParts.push(runs.length === 1 ? '1 run' : runs.length + ' runs');
  if (typeof data.generator === 'string' && data.generator) subtitleParts.push(data.generator);
  document.getElementById('subtitle').textContent = subtitleParts.join(' \u00b7 ');

  slider.min = '0';
  slider.max = String(duration);
  slider.value = '0';

  function outcomeClass(outcome) {
    var o = outcome.toLowerCase();
    if (o === 'reached' || o === 'success' || o === 'succeeded' || o === 'goal') return 'good';
    if (/coll|crash|fail|error|stuck|flip/.test(o)) return 'bad';
    return 'other';
  }

  runs.forEach(function (run) {
    var row = document.createElement('div');
    row.className = 'legend-entry';
    row.title = 'Click to show or hide this run';
    var swatch = document.createElement('span');
    swatch.className = 'swatch';
    swatch.style.background = cssColor(run.color);
    var text = document.createElement('div');
    text.className = 'legend-text';
    var name = document.createElement('span');
    name.className = 'legend-label';
    name.textContent = run.label;
    var detail = document.createElement('span');
    detail.className = 'legend-detail';
    detail.appendChild(document.createTextNode(run.vehicleType + (run.outcome ? ' \u00b7 ' : '')));
    if (run.outcome) {
      var outcome = document.createElement('span');
      outcome.className = 'outcome ' + outcomeClass(run.outcome);
      outcome.textContent = run.outcome;
      detail.appendChild(outcome);
    }
    text.appendChild(name);
    text.appendChild(detail);
    row.appendChild(swatch);
    row.appendChild(text);
    row.addEventListener('click', function () {
      run.group.visible = !run.group.visible;
      row.classList.toggle('hidden-run', !run.group.visible);
      requestRender();
    });
    legend.appendChild(row);
  });
  if (runs.length === 0) legend.style.display = 'none';

  function formatClock(t) {
    return t.toFixed(1) + ' s / ' + duration.toFixed(1) + ' s';
  }

  // ---------------------------------------------------------------- camera framing and clipping

  var controls = null;

  function defaultCamera() {
    // Look along the first run's overall travel direction, from behind and above (35 degrees down).
    var heading = Math.PI / 2;
    for (var k = 0; k < runs.length; k++) {
      var pts = runs[k].points;
      if (pts.length >= 2) {
        var dx = pts[pts.length - 1].x - pts[0].x;
        var dy = pts[pts.length - 1].y - pts[0].y;
        if (Math.hypot(dx, dy) > 1e-6) {
          heading = Math.atan2(dy, dx);
          break;
        }
      }
    }
    var down = THREE.MathUtils.degToRad(35);
    var forward = new THREE.Vector3(Math.cos(heading) * Math.cos(down), Math.sin(heading) * Math.cos(down),
                                    -Math.sin(down));
    var right = new THREE.Vector3().crossVectors(forward, camera.up).normalize();
    var up = new THREE.Vector3().crossVectors(right, forward).normalize();
    var tanV = Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2);
    var tanH = tanV * camera.aspect;
    // Smallest distance for which every corner of the bounds is inside the view, plus a margin for the UI.
    var distance = 0;
    for (var corner = 0; corner < 8; corner++) {
      var v = new THREE.Vector3(corner & 1 ? boundsMax.x : boundsMin.x, corner & 2 ? boundsMax.y : boundsMin.y,
                                corner & 4 ? boundsMax.z : boundsMin.z).sub(centre);
      var depth = v.dot(forward);
      distance = Math.max(distance, -depth + Math.abs(v.dot(right)) / tanH, -depth + Math.abs(v.dot(up)) / tanV);
    }
    distance = Math.max(distance * 1.04, 1e-3);
    camera.position.copy(centre).addScaledVector(forward, -distance);
    camera.lookAt(centre);
    if (controls) controls.target.copy(centre);
  }

  function updateClipping() {
    var distance = camera.position.distanceTo(centre);
    var far = (distance + reachRadius) * 1.05;
    var near = Math.max((distance - reachRadius) * 0.95, far * 2e-5);
    if (near !== camera.near || far !== camera.far) {
      camera.near = near;
      camera.far = far;
      camera.updateProjectionMatrix();
    }
  }

  function applyFov(text) {
    var fov = text === undefined ? DEFAULT_FOV_DEG : Number(text);
    camera.fov = isFinite(fov) && fov > 0.1 && fov < 179 ? fov : DEFAULT_FOV_DEG;
    camera.updateProjectionMatrix();
  }

  function applyCamera(text) {
    var v = parseNumberList(text, 6);
    if (!v) return false;
    camera.position.set(v[0], v[1], v[2]);
    controls.target.set(v[3], v[4], v[5]);
    camera.lookAt(controls.target);
    return true;
  }

  // ---------------------------------------------------------------- views

  function applyView(isSilhouette) {
    silhouette = isSilhouette;
    document.body.classList.toggle('silhouette', silhouette);
    scene.background = silhouette ? new THREE.Color(0x000000) : null;
    staticMeshes.forEach(function (s) { s.mesh.material = silhouette ? whiteMaterial : s.material; });
    decorGroup.visible = !silhouette;
    moverGroup.visible = !silhouette;
    runGroup.visible = !silhouette;
  }

  // ---------------------------------------------------------------- rendering and state

  var renderPending = false;

  function writeState() {
    var ds = document.body.dataset;
    ds.time = String(currentTime);
    ds.vehicles = runs.map(function (run) {
      return String(run.position.x) + ',' + String(run.position.y) + ',' + String(run.position.z);
    }).join(';');
    var shown = 0;
    runs.forEach(function (run) { shown += run.scanCount; });
    ds.scanPoints = String(shown);
    ds.ready = '1';
  }

  function renderNow() {
    renderPending = false;
    updateClipping();
    renderer.render(scene, camera);
  }

  function requestRender() {
    if (renderPending) return;
    renderPending = true;
    window.requestAnimationFrame(function () {
      if (renderPending) renderNow();
    });
  }

  function setTime(t) {
    currentTime = Math.min(Math.max(t, 0), duration);
    runs.forEach(function (run) { updateRun(run, currentTime); });
    updateMovers(currentTime);
    clock.textContent = formatClock(currentTime);
    renderNow();
    writeState();
  }

  // ---------------------------------------------------------------- playback

  var playing = false;
  var lastTick = 0;

  function setPlaying(on) {
    playing = on && duration > 0;
    playButton.textContent = playing ? 'Pause' : 'Play';
    if (playing) {
      if (currentTime >= duration) {
        slider.value = '0';
        setTime(0);
      }
      lastTick = performance.now();
      window.requestAnimationFrame(tick);
    }
  }

  function tick(now) {
    if (!playing) return;
    var elapsed = Math.min(Math.max((now - lastTick) / 1000, 0), 0.5);   // no jump after a hidden tab
    lastTick = now;
    var t = Math.min(currentTime + elapsed * Number(speedSelect.value), duration);
    slider.value = String(t);
    setTime(t);
    if (t >= duration) {
      setPlaying(false);
      return;
    }
    window.requestAnimationFrame(tick);
  }

  // The range input keeps only about 15 significant digits; a time requested through the hash is
  // used exactly when the slider holds its rounded value.
  var requestedTime = null;

  slider.addEventListener('input', function () {
    var t = parseFloat(slider.value);
    if (requestedTime !== null && Math.abs(requestedTime - t) <= 1e-12 * Math.max(1, Math.abs(t))) t = requestedTime;
    requestedTime = null;
    setTime(isFinite(t) ? t : 0);
  });
  playButton.addEventListener('click', function () {
    setPlaying(!playing);
    playButton.blur();
  });
  speedSelect.addEventListener('change', function () { speedSelect.blur(); });
  window.addEventListener('keydown', function (event) {
    if (event.code !== 'Space' && event.key !== ' ') return;
    var tag = event.target && event.target.tagName;
    if (tag === 'SELECT' || tag === 'TEXTAREA' || (tag === 'INPUT' && event.target.type !== 'range')) return;
    event.preventDefault();
    setPlaying(!playing);
  });
  window.addEventListener('resize', function () {
    camera.aspect = window.innerWidth / Math.max(1, window.innerHeight);
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
    renderNow();
  });

  // ---------------------------------------------------------------- start

  function applyHash(initial) {
    var h = parseHash();
    applyView(h.view === 'silhouette');
    applyFov(h.fov);
    if (!applyCamera(h.camera) && initial) defaultCamera();
    if (h.t !== undefined && h.t !== '' && isFinite(Number(h.t))) {
      requestedTime = Math.min(Math.max(Number(h.t), 0), duration);
      slider.value = String(requestedTime);
      slider.dispatchEvent(new Event('input', { bubbles: true }));
    } else {
      setTime(currentTime);
    }
  }

  applyFov(hash.fov);
  defaultCamera();
  controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(centre);
  controls.update();
  controls.addEventListener('change', requestRender);
  window.addEventListener('hashchange', function () { applyHash(false); });
  applyHash(true);
})();
