/* reflect-report's viewer: plain ES5 in one closure, so that the page
 * runs as a file in any browser, offline, with nothing fetched. */
(function () {
	'use strict';

	/* What went wrong while the page ran, for the self-test: uncaught
	 * errors and whatever the page says on the console as an error. */
	var problems = [];
	window.addEventListener('error', function (e) {
		problems.push('error: ' + (e.message || e.type));
	}, true);
	if (window.console && console.error) {
		var consoleError = console.error;
		console.error = function () {
			problems.push('console.error: ' + Array.prototype.join.call(arguments, ' '));
			return consoleError.apply(console, arguments);
		};
	}

	function $(id) { return document.getElementById(id); }

	var R = JSON.parse($('report-data').textContent);
	var npic = R.pictures.length;
	var W = R.width, H = R.height;
	var st = { a: 0, b: 0, wipe: 100, e: R.stop0, s: 1, tx: 0, ty: 0 };
	var picsA = [], picsB = [], heats = [];

	function shot(i, e) { return $('shot-' + i + '-' + e).src; }

	function make(parent, src, alt) {
		var img = document.createElement('img');
		img.width = W;
		img.height = H;
		img.alt = alt;
		img.draggable = false;
		img.src = src;
		parent.appendChild(img);
		return img;
	}

	/* Every picture stands in the viewer at once, one of them shown: a
	 * flip swaps which is shown and never waits for an image to decode,
	 * as a flip must be instant to be seen. */
	function build() {
		var i, o;
		for (i = 0; i < npic; i++) {
			picsA.push(make($('pics-a'), shot(i, st.e), R.pictures[i].name));
			picsB.push(make($('wipe-b'), shot(i, st.e), R.pictures[i].name));
			heats.push(i ? make($('layer-heat'), $('heat-' + i).src,
			                    'FLIP map of ' + R.pictures[i].name) : null);
			o = document.createElement('option');
			o.value = i;
			o.textContent = i + ': ' + R.pictures[i].name;
			$('sel-a').appendChild(o);
			$('sel-b').appendChild(o.cloneNode(true));
		}
		$('exposure').disabled = R.stops.length < 2;
		$('wipe-line').style.height = H + 'px';
		$('wipe-b').style.width = W + 'px';
		$('wipe-b').style.height = H + 'px';
	}

	function stopText(v) {
		return (v > 0 ? '+' : '') + v + (v === 1 || v === -1 ? ' stop' : ' stops');
	}

	/* Shows the state: the pictures, the wipe, the map, the exposure. */
	function show() {
		var i, hm = st.a || st.b || (npic > 1 ? 1 : 0), rows, cards;
		for (i = 0; i < npic; i++) {
			picsA[i].className = i === st.a ? 'on' : '';
			picsB[i].className = i === st.b ? 'on' : '';
			if (heats[i])
				heats[i].className = i === hm ? 'on' : '';
		}
		$('wipe-b').style.clipPath = 'inset(0 0 0 ' + st.wipe + '%)';
		$('wipe-b').style.webkitClipPath = 'inset(0 0 0 ' + st.wipe + '%)';
		$('wipe-line').style.left = (st.wipe * W / 100) + 'px';
		$('wipe-line').style.display = st.wipe < 100 && st.wipe > 0 ? 'block' : 'none';
		$('tag-a').textContent = 'A ' + st.a + ': ' + R.pictures[st.a].name;
		$('tag-b').textContent = st.wipe < 100 ? 'B ' + st.b + ': ' + R.pictures[st.b].name : '';
		$('tag-b').style.display = st.wipe < 100 ? '' : 'none';
		$('tag-heat').textContent = hm ? 'FLIP map: ' + R.pictures[hm].name : 'no mode: no map';
		$('sel-a').value = String(st.a);
		$('sel-b').value = String(st.b);
		$('wipe').value = String(st.wipe);
		$('exposure').value = String(st.e);
		$('exposure-value').textContent = R.linear ? stopText(R.stops[st.e])
		                                           : 'display pictures';
		rows = document.querySelectorAll('#errors tbody tr');
		for (i = 0; i < rows.length; i++)
			rows[i].className = +rows[i].getAttribute('data-pic') === st.a ? 'shown' : '';
		cards = document.querySelectorAll('.card');
		for (i = 0; i < cards.length; i++)
			cards[i].style.outline = +cards[i].getAttribute('data-pic') === st.a
			                         ? '2px solid #4a7bd0' : '';
		place();
	}

	/* Zoom and pan, one for both views: a pixel of the picture and the
	 * same pixel of its map stay side by side. */
	function place() {
		var t = 'translate(' + st.tx + 'px,' + st.ty + 'px) scale(' + st.s + ')';
		$('layer-pic').style.transform = t;
		$('layer-heat').style.transform = t;
		/* one screen pixel at any zoom: a width, as a border's is
		 * rounded up to a pixel before the scale */
		$('wipe-line').style.width = (1 / st.s) + 'px';
	}

	function fit() {
		var v = $('view-pic'), w = v.clientWidth, h = v.clientHeight;
		st.s = w > 0 && h > 0 ? Math.min(w / W, h / H) : 1;
		st.tx = (w - st.s * W) / 2;
		st.ty = (h - st.s * H) / 2;
		place();
	}

	function setExposure(e) {
		var i;
		if (e < 0 || e >= R.stops.length || e === st.e)
			return;
		st.e = e;
		for (i = 0; i < npic; i++) {
			picsA[i].src = shot(i, e);
			picsB[i].src = shot(i, e);
		}
		show();
	}

	function zoomAt(view, cx, cy, factor) {
		var r = view.getBoundingClientRect(), x = cx - r.left, y = cy - r.top;
		var s = Math.max(1 / 64, Math.min(256, st.s * factor));
		st.tx = x - (x - st.tx) * (s / st.s);
		st.ty = y - (y - st.ty) * (s / st.s);
		st.s = s;
		place();
	}

	function wire() {
		var views = [$('view-pic'), $('view-heat')], drag = null, i;

		for (i = 0; i < views.length; i++) {
			views[i].addEventListener('wheel', function (e) {
				e.preventDefault();
				zoomAt(this, e.clientX, e.clientY, e.deltaY < 0 ? 1.25 : 0.8);
			});
			views[i].addEventListener('mousedown', function (e) {
				if (e.button !== 0)
					return;
				e.preventDefault();
				drag = { x: e.clientX, y: e.clientY, view: this };
				this.className = 'view dragging';
			});
			views[i].addEventListener('dblclick', fit);
		}
		window.addEventListener('mousemove', function (e) {
			if (!drag)
				return;
			st.tx += e.clientX - drag.x;
			st.ty += e.clientY - drag.y;
			drag.x = e.clientX;
			drag.y = e.clientY;
			place();
		});
		window.addEventListener('mouseup', function () {
			if (drag)
				drag.view.className = 'view';
			drag = null;
		});
		$('wipe').addEventListener('input', function () {
			st.wipe = +this.value;
			show();
		});
		$('exposure').addEventListener('input', function () { setExposure(+this.value); });
		$('sel-a').addEventListener('change', function () { st.a = +this.value; show(); });
		$('sel-b').addEventListener('change', function () { st.b = +this.value; show(); });
		$('fit').addEventListener('click', fit);
		window.addEventListener('resize', fit);
		$('one').addEventListener('click', function () {
			var v = $('view-pic');
			zoomAt(v, v.getBoundingClientRect().left + v.clientWidth / 2,
			       v.getBoundingClientRect().top + v.clientHeight / 2, 1 / st.s);
		});
		document.addEventListener('keydown', function (e) {
			var tag = e.target && e.target.tagName, k = e.key;
			if (e.ctrlKey || e.metaKey || e.altKey)
				return;
			if (/^[0-9]$/.test(k) && +k < npic) {
				st.a = +k;
			} else if ((k === 'ArrowRight' || k === 'ArrowLeft') &&
			           tag !== 'INPUT' && tag !== 'SELECT') {
				st.a = (st.a + (k === 'ArrowRight' ? 1 : npic - 1)) % npic;
			} else if (k === '+' || k === '=' || k === '-') {
				/* '=' is '+' without shift on most keyboards */
				setExposure(st.e + (k === '-' ? -1 : 1));
				return;
			} else {
				return;
			}
			e.preventDefault();
			show();
		});
		var rows = document.querySelectorAll('#errors tbody tr, .card');
		for (i = 0; i < rows.length; i++)
			rows[i].addEventListener('click', function () {
				st.a = +this.getAttribute('data-pic');
				show();
			});
		var heads = document.querySelectorAll('#errors th');
		for (i = 0; i < heads.length; i++)
			heads[i].addEventListener('click', sortBy);
	}

	/* Sorts the table by a column: numbers as numbers (a figure not
	 * given last), names as text; again reverses. */
	function sortBy() {
		var th = this, col = th.cellIndex, up = th.className !== 'up';
		var body = document.querySelector('#errors tbody');
		var rows = Array.prototype.slice.call(body.rows), heads = th.parentNode.cells, i;
		function key(r) {
			var c = r.cells[col], v = c.getAttribute('data-v');
			return v === null ? c.textContent : v === '' ? null : +v;
		}
		rows.sort(function (p, q) {
			var a = key(p), b = key(q);
			if (a === b)
				return 0;
			if (a === null)
				return 1;
			if (b === null)
				return -1;
			return (a < b ? -1 : 1) * (up ? 1 : -1);
		});
		for (i = 0; i < rows.length; i++)
			body.appendChild(rows[i]);
		for (i = 0; i < heads.length; i++)
			heads[i].className = '';
		th.className = up ? 'up' : 'down';
	}

	/* The self-test (the page opened as ...#selftest): drives the page
	 * as a user would and checks what it shows; the verdict is written
	 * into the page, where a headless browser's dump of it is read. */
	function selftest() {
		var fails = [], n = 0, e, i, imgs, names, rows, sum0, sum1, p, q, r, t0, t1, th, v;
		function check(ok, what) {
			n++;
			if (!ok)
				fails.push(what);
		}
		function key(k) {
			document.dispatchEvent(new KeyboardEvent('keydown', { key: k, bubbles: true }));
		}
		function shown(list) {
			for (var j = 0; j < list.length; j++)
				if (list[j] && list[j].className === 'on' &&
				    getComputedStyle(list[j]).display !== 'none')
					return j;
			return -1;
		}
		/* the sum of a shown picture's pixels, as the browser decoded it */
		function pixels(img) {
			var c = document.createElement('canvas'), x, d, s = 0, j;
			c.width = W;
			c.height = H;
			x = c.getContext('2d');
			x.drawImage(img, 0, 0);
			d = x.getImageData(0, 0, W, H).data;
			for (j = 0; j < d.length; j++)
				s += d[j];
			return s;
		}
		function at(xf) {
			var rect = $('view-pic').getBoundingClientRect();
			return document.elementFromPoint(rect.left + st.tx + st.s * W * xf,
			                                 rect.top + st.ty + st.s * H / 2);
		}

		imgs = document.images;
		/* the store's, the cards' maps, the viewer's */
		check(imgs.length === npic * R.stops.length + 2 * (npic - 1) + 2 * npic,
		      'the page holds ' + imgs.length + ' images');
		for (i = 0; i < imgs.length; i++)
			check(imgs[i].complete && imgs[i].naturalWidth === W &&
			      imgs[i].naturalHeight === H,
			      'image ' + (imgs[i].id || imgs[i].alt) + ' is not decoded (' +
			      imgs[i].naturalWidth + 'x' + imgs[i].naturalHeight + ')');

		rows = document.querySelectorAll('#errors tbody tr');
		check(rows.length === npic - 1, 'the table has ' + rows.length + ' rows');
		names = [];
		for (i = 0; i < rows.length; i++)
			names.push(rows[i].cells[0].textContent);
		for (i = 1; i < npic; i++)
			check(names.indexOf(R.pictures[i].name) >= 0,
			      'the table lists no ' + R.pictures[i].name);

		$('view-pic').scrollIntoView();
		fit();
		check(shown(picsA) === 0, 'the truth is not shown first');
		sum0 = pixels(picsA[shown(picsA)]);
		key('1');
		check(st.a === 1 && shown(picsA) === 1, 'key 1 does not show mode 1');
		sum1 = pixels(picsA[shown(picsA)]);
		check(sum0 !== sum1, 'key 1 shows the same pixels as the truth');
		check(shown(heats) === 1, 'key 1 does not show mode 1\'s map');
		key('ArrowRight');
		check(shown(picsA) === 2 % npic, 'the right arrow does not show the next');
		check(npic < 3 || shown(heats) === 2, 'the right arrow does not show its map');
		key('ArrowLeft');
		key('ArrowLeft');
		check(shown(picsA) === 0, 'the left arrow does not go back to the truth');
		key('0');
		check(shown(picsA) === 0, 'key 0 does not show the truth');

		/* the wipe: B on the right of the slider, A on its left */
		st.b = 1;
		show();
		check(at(0.75) === picsA[0], 'with the slider at 100, B shows');
		$('wipe').value = '50';
		$('wipe').dispatchEvent(new Event('input', { bubbles: true }));
		check(st.wipe === 50, 'the slider does not move the wipe');
		check(at(0.25) === picsA[0], 'left of the wipe is not A (' + at(0.25) + ')');
		check(at(0.75) === picsB[1], 'right of the wipe is not B (' + at(0.75) + ')');
		$('wipe').value = '0';
		$('wipe').dispatchEvent(new Event('input', { bubbles: true }));
		check(at(0.25) === picsB[1], 'with the slider at 0, A shows');

		/* zoom and pan, the same in both views */
		p = $('view-pic').getBoundingClientRect();
		t0 = st.s;
		v = $('layer-heat').style.transform;
		$('view-pic').dispatchEvent(new WheelEvent('wheel', { deltaY: -100, bubbles: true,
			cancelable: true, clientX: p.left + 10, clientY: p.top + 10 }));
		check(st.s > t0, 'the wheel does not zoom in');
		check($('layer-pic').style.transform === $('layer-heat').style.transform &&
		      $('layer-heat').style.transform !== v, 'the views do not zoom together');
		t1 = st.tx;
		q = { bubbles: true, button: 0, clientX: p.left + 20, clientY: p.top + 20 };
		$('view-heat').dispatchEvent(new MouseEvent('mousedown', q));
		q.clientX += 30;
		window.dispatchEvent(new MouseEvent('mousemove', q));
		window.dispatchEvent(new MouseEvent('mouseup', q));
		check(st.tx === t1 + 30, 'dragging the map does not pan');
		check($('layer-pic').style.transform === $('layer-heat').style.transform,
		      'the views do not pan together');
		fit();

		/* the exposure, where the pictures are linear: a stop either
		 * side of the first, which may be the lowest or the highest */
		if (R.stops.length > 1) {
			v = picsA[0].src;
			e = R.stop0 + 1 < R.stops.length ? R.stop0 + 1 : R.stop0 - 1;
			$('exposure').value = String(e);
			$('exposure').dispatchEvent(new Event('input', { bubbles: true }));
			check(picsA[0].src === shot(0, e) && picsA[0].src !== v,
			      'the exposure does not change the pictures');
			setExposure(R.stops.length - 1);
			key('-');
			check(st.e === R.stops.length - 2 && picsA[0].src === shot(0, st.e),
			      'the key - does not lower the exposure');
			key('=');
			check(st.e === R.stops.length - 1, 'the key = does not raise the exposure');
			setExposure(R.stop0);
		}

		/* sorting: ascending by FLIP, then descending */
		th = document.querySelectorAll('#errors th')[3];
		th.click();
		r = Array.prototype.map.call(document.querySelectorAll('#errors tbody tr'),
			function (row) { return +row.cells[3].getAttribute('data-v'); });
		for (i = 1; i < r.length; i++)
			check(r[i - 1] <= r[i], 'FLIP is not sorted up');
		th.click();
		check(+document.querySelector('#errors tbody tr').cells[3].getAttribute('data-v') ===
		      Math.max.apply(null, r), 'FLIP is not sorted down');

		st.a = 0;
		st.b = 0;
		st.wipe = 100;
		show();
		check(problems.length === 0, problems.join('; '));
		$('selftest').textContent = fails.length ? 'selftest: FAIL ' + fails.length + ' of ' +
			n + ' checks: ' + fails.join('; ') : 'selftest: pass, ' + n + ' checks';
	}

	build();
	wire();
	show();
	window.addEventListener('load', function () {
		fit();
		var hash = location.hash;
		if (hash !== '#selftest' && hash !== '#selftest-colour')
			return;
		try {
			selftest();
		} catch (err) {
			$('selftest').textContent = 'selftest: FAIL: ' + err;
		}
		/* For a browser that can take a screenshot but not hand back
		 * the page (Firefox headless): the whole page one colour, pure
		 * green for a pass and pure red for a failure. */
		if (hash === '#selftest-colour') {
			document.body.style.visibility = 'hidden';
			document.documentElement.style.background =
				/^selftest: pass/.test($('selftest').textContent) ? '#00ff00' : '#ff0000';
		}
	});
}());
